//! One degree of freedom through a contact law: a mass `m` moving along the normal or
//! the tangential direction, pushed by an external force `f(t)`, a viscous dashpot `c`
//! and the contact, `m x'' = f(t) - c x' - F_contact(x, history)`.
//!
//! **Scheme.** Velocity Verlet (second order, symplectic without the dashpot): the
//! half-step velocity `v + a dt / 2`, the new position, the contact force there (a
//! trial of the law), the new acceleration with the dashpot on the half-step velocity,
//! the velocity's second half step. A step whose contact force changes by more than
//! `max_jump` of the force scale is rejected ([`crate::ContactLaw::rollback`]) and
//! retried at half the time step, down to `dt_min`; accepted steps let the step grow
//! again by a quarter up to `dt`. First contact, a contact lost, a hard impact are the
//! steps where this matters; a smooth motion runs at `dt`.

use crate::law::{ContactLaw, Motion};
use crate::{bad, Result};

/// Which way the mass moves, and the other coordinate held.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Axis {
    /// Along the normal: x is the approach; the tangential displacement is held.
    Normal { tangential: f64 },
    /// Along the tangential direction: x is the displacement; the approach is held.
    Tangential { approach: f64 },
    /// Along the tangential direction under a normal approach that oscillates:
    /// `approach (1 + amplitude sin(omega t + phase))` (Section 7's normal and
    /// tangential forces oscillating together, in time); x is the displacement.
    /// `amplitude` in [0, 1), `omega` [rad / time], `phase` [rad].
    TangentialWave {
        approach: f64,
        amplitude: f64,
        omega: f64,
        phase: f64,
    },
}

/// The problem and the scheme's settings.
pub struct Oscillator<'a> {
    pub mass: f64,
    /// Viscous dashpot [force x time / length], >= 0.
    pub damping: f64,
    /// The external force on the mass at time t [force].
    pub drive: &'a dyn Fn(f64) -> f64,
    pub axis: Axis,
    /// The time step, and the smallest a rejection may reach [time].
    pub dt: f64,
    pub dt_min: f64,
    /// The largest change of the contact force in a step, over `force_scale`.
    pub max_jump: f64,
    pub force_scale: f64,
}

/// One accepted step's end.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    pub t: f64,
    pub x: f64,
    pub v: f64,
    /// The contact force along the axis [force].
    pub force: f64,
    /// The normal force (equal to `force` on the normal axis) [force].
    pub normal: f64,
    pub contact_area: f64,
    /// Slip energy of the step [force x length].
    pub dissipated: f64,
    /// The law's solver work of the step (3D iterations, summed over its trials).
    pub iterations: usize,
}

/// What a run did besides its samples.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Counts {
    pub accepted: usize,
    pub rejected: usize,
    /// Trials of the law (accepted and rejected).
    pub trials: usize,
}

/// Where a run stops.
pub enum Stop<'a> {
    /// At time `t`.
    At(f64),
    /// When `until` holds for the last sample (checked after each accepted step), or at
    /// `t_max`.
    When {
        until: &'a dyn Fn(&Sample) -> bool,
        t_max: f64,
    },
}

/// Largest accepted steps of one run (a guard against a stop that never comes).
pub const MAX_STEPS: usize = 100_000_000;

impl Oscillator<'_> {
    fn check(&self) -> Result<()> {
        for (name, v) in [
            ("mass", self.mass),
            ("dt", self.dt),
            ("force_scale", self.force_scale),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return bad(format!("{name} = {v} must be finite and > 0"));
            }
        }
        if !(self.damping.is_finite() && self.damping >= 0.0) {
            return bad(format!(
                "damping = {} must be finite and >= 0",
                self.damping
            ));
        }
        if !(self.dt_min.is_finite() && self.dt_min > 0.0 && self.dt_min <= self.dt) {
            return bad(format!(
                "dt_min = {} must lie in (0, dt = {}]",
                self.dt_min, self.dt
            ));
        }
        if let Axis::TangentialWave {
            approach,
            amplitude,
            omega,
            phase,
        } = self.axis
        {
            let finite = approach.is_finite() && phase.is_finite();
            if !(finite && omega.is_finite() && omega >= 0.0 && (0.0..1.0).contains(&amplitude)) {
                return bad(format!(
                    "normal wave: approach = {approach} and phase = {phase} must be finite, omega = {omega} finite and >= 0, amplitude = {amplitude} in [0, 1)"
                ));
            }
        }
        if !(self.max_jump.is_finite() && self.max_jump > 0.0) {
            return bad(format!(
                "max_jump = {} must be finite and > 0",
                self.max_jump
            ));
        }
        Ok(())
    }

    /// The motion of a step ending at time `t` with the mass at `x`.
    fn motion(&self, x: f64, t: f64, dt: f64) -> Motion {
        match self.axis {
            Axis::Normal { tangential } => Motion {
                normal: x,
                tangential,
                dt,
            },
            Axis::Tangential { approach } => Motion {
                normal: approach,
                tangential: x,
                dt,
            },
            Axis::TangentialWave {
                approach,
                amplitude,
                omega,
                phase,
            } => Motion {
                normal: approach * (1.0 + amplitude * (omega * t + phase).sin()),
                tangential: x,
                dt,
            },
        }
    }

    fn along(&self, f: &crate::Forces) -> f64 {
        match self.axis {
            Axis::Normal { .. } => f.normal,
            Axis::Tangential { .. } | Axis::TangentialWave { .. } => f.tangential,
        }
    }

    /// Integrates from `(x0, v0)` at t = 0 (the law's accepted state is the start's
    /// history; the first sample is the start) until `stop`; `every`: keep one sample
    /// in so many accepted steps (the last always).
    pub fn run(
        &self,
        law: &mut dyn ContactLaw,
        (x0, v0): (f64, f64),
        stop: Stop,
        every: usize,
    ) -> Result<(Vec<Sample>, Counts)> {
        self.check()?;
        if !(x0.is_finite() && v0.is_finite()) {
            return bad(format!("x0 = {x0} and v0 = {v0} must be finite"));
        }
        let every = every.max(1);
        let t_end = match stop {
            Stop::At(t) | Stop::When { t_max: t, .. } => t,
        };
        if !(t_end.is_finite() && t_end > 0.0) {
            return bad(format!("the end time {t_end} must be finite and > 0"));
        }
        let mut counts = Counts::default();
        // The start: the contact force at x0 accepted as the history's first state.
        let f0 = law.trial(self.motion(x0, 0.0, self.dt))?;
        counts.trials += 1;
        law.commit()?;
        let mut s = Sample {
            t: 0.0,
            x: x0,
            v: v0,
            force: self.along(&f0),
            normal: f0.normal,
            contact_area: f0.contact_area,
            dissipated: 0.0,
            iterations: f0.iterations,
        };
        let mut a = ((self.drive)(0.0) - s.force - self.damping * v0) / self.mass;
        let mut out = vec![s];
        let mut dt = self.dt;
        let mut iterations = 0;
        while s.t < t_end {
            if counts.accepted >= MAX_STEPS {
                return bad(format!(
                    "{MAX_STEPS} steps did not reach the end time {t_end}: raise dt"
                ));
            }
            let h = dt.min(t_end - s.t);
            let half = s.v + 0.5 * h * a;
            let x = s.x + h * half;
            let f = law.trial(self.motion(x, s.t + h, h))?;
            counts.trials += 1;
            iterations += f.iterations;
            let force = self.along(&f);
            let jump = (force - s.force).abs() / self.force_scale;
            if jump > self.max_jump && h > self.dt_min {
                law.rollback();
                counts.rejected += 1;
                dt = (0.5 * h).max(self.dt_min);
                continue;
            }
            law.commit()?;
            counts.accepted += 1;
            let t = s.t + h;
            let a_new = ((self.drive)(t) - force - self.damping * half) / self.mass;
            s = Sample {
                t,
                x,
                v: half + 0.5 * h * a_new,
                force,
                normal: f.normal,
                contact_area: f.contact_area,
                dissipated: f.dissipated,
                iterations,
            };
            iterations = 0;
            a = a_new;
            dt = (1.25 * dt).min(self.dt);
            let stop_now = match &stop {
                Stop::When { until, .. } => until(&s),
                Stop::At(_) => false,
            };
            if counts.accepted % every == 0 || stop_now || s.t >= t_end {
                out.push(s);
            }
            if stop_now {
                break;
            }
        }
        Ok((out, counts))
    }
}

/// A free body moving in the plane of the normal and the tangential direction, no
/// external force: `m_k x_k'' = -F_k(x, history)` for `x = (approach, tangential
/// displacement)`, each with its own mass; the same scheme as [`Oscillator`], a step
/// rejected where the contact force's magnitude changes by more than `max_jump` of
/// `force_scale`. A body that also turns freely about its centre (moment of inertia
/// `I`, the contact at distance `R`) moves its contact point tangentially as a mass
/// `m / (1 + m R^2 / I)` would: give that as the tangential mass, and the tangential
/// coordinate is the contact point's displacement (translation and rolling).
pub struct Planar {
    /// The normal and the tangential mass [mass].
    pub mass: [f64; 2],
    pub dt: f64,
    pub dt_min: f64,
    pub max_jump: f64,
    pub force_scale: f64,
}

/// One accepted step's end of a [`Planar`] run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanarSample {
    pub t: f64,
    /// Approach and tangential displacement [length].
    pub x: [f64; 2],
    /// Their velocities [length / time].
    pub v: [f64; 2],
    /// The contact's forces at the step's end.
    pub forces: crate::Forces,
}

impl Planar {
    /// Integrates from `(x0, v0)` at t = 0 until `until` holds for an accepted sample
    /// or at `t_max`; every accepted step is a sample.
    pub fn run(
        &self,
        law: &mut dyn ContactLaw,
        (x0, v0): ([f64; 2], [f64; 2]),
        until: &dyn Fn(&PlanarSample) -> bool,
        t_max: f64,
    ) -> Result<(Vec<PlanarSample>, Counts)> {
        if !(self.mass[1].is_finite() && self.mass[1] > 0.0) {
            return bad(format!(
                "tangential mass = {} must be finite and > 0",
                self.mass[1]
            ));
        }
        Oscillator {
            mass: self.mass[0],
            damping: 0.0,
            drive: &|_| 0.0,
            axis: Axis::Normal { tangential: 0.0 },
            dt: self.dt,
            dt_min: self.dt_min,
            max_jump: self.max_jump,
            force_scale: self.force_scale,
        }
        .check()?;
        if !(x0.iter().chain(&v0).all(|v| v.is_finite()) && t_max.is_finite() && t_max > 0.0) {
            return bad(format!(
                "x0 = {x0:?}, v0 = {v0:?} and t_max = {t_max} must be finite (t_max > 0)"
            ));
        }
        let motion = |x: [f64; 2], dt: f64| Motion {
            normal: x[0],
            tangential: x[1],
            dt,
        };
        let along = |f: &crate::Forces| [f.normal, f.tangential];
        let mut counts = Counts::default();
        let f0 = law.trial(motion(x0, self.dt))?;
        counts.trials += 1;
        law.commit()?;
        let mut s = PlanarSample {
            t: 0.0,
            x: x0,
            v: v0,
            forces: f0,
        };
        let accel = |f: [f64; 2]| [-f[0] / self.mass[0], -f[1] / self.mass[1]];
        let mut a = accel(along(&f0));
        let mut out = vec![s];
        let mut dt = self.dt;
        while s.t < t_max {
            if counts.accepted >= MAX_STEPS {
                return bad(format!(
                    "{MAX_STEPS} steps did not reach the end time {t_max}: raise dt"
                ));
            }
            let h = dt.min(t_max - s.t);
            let half = [0, 1].map(|k| s.v[k] + 0.5 * h * a[k]);
            let x = [0, 1].map(|k| s.x[k] + h * half[k]);
            let f = law.trial(motion(x, h))?;
            counts.trials += 1;
            let (new, old) = (along(&f), along(&s.forces));
            let jump = (new[0] - old[0]).hypot(new[1] - old[1]) / self.force_scale;
            if jump > self.max_jump && h > self.dt_min {
                law.rollback();
                counts.rejected += 1;
                dt = (0.5 * h).max(self.dt_min);
                continue;
            }
            law.commit()?;
            counts.accepted += 1;
            let a_new = accel(new);
            s = PlanarSample {
                t: s.t + h,
                x,
                v: [0, 1].map(|k| half[k] + 0.5 * h * a_new[k]),
                forces: f,
            };
            a = a_new;
            dt = (1.25 * dt).min(self.dt);
            out.push(s);
            if until(&s) {
                break;
            }
        }
        Ok((out, counts))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::law::{Motion, Springs};
    use mrd::profile::{Profile, Shape};
    use mrd::reference::hertz_impact;
    use std::f64::consts::PI;

    /// The contact time of the first contact of a run (x > 0), by linear interpolation
    /// of the crossings of x = 0, and the speeds at them.
    fn contact(samples: &[Sample]) -> (f64, f64, f64) {
        let cross = |i: usize| {
            let (a, b) = (samples[i], samples[i + 1]);
            let w = a.x / (a.x - b.x);
            (a.t + w * (b.t - a.t), a.v + w * (b.v - a.v))
        };
        let start = samples
            .windows(2)
            .position(|w| w[0].x <= 0.0 && w[1].x > 0.0)
            .unwrap();
        let end = start
            + samples[start..]
                .windows(2)
                .position(|w| w[0].x > 0.0 && w[1].x <= 0.0)
                .unwrap();
        let (t0, v_in) = cross(start);
        let (t1, v_out) = cross(end);
        (t1 - t0, v_in, v_out)
    }

    /// Hertz's impact on MRD's springs: contact time and largest force against Hertz's
    /// impact solution (Johnson 11.4) within 1e-3 at 4000 springs and t_c / 4000 steps,
    /// the restitution coefficient 1 within 1e-4.
    #[test]
    fn hertz_impact_on_mrd_springs() {
        let (e, r, m, v) = (1.0, 1.0, 1e-3, 0.05);
        let profile = Profile::single(Shape::paraboloid(r).unwrap());
        let dmax = hertz_impact::max_approach(e, r, m, v);
        let tc = hertz_impact::duration(e, r, m, v);
        let mut law = Springs::body(&profile, e, 4000, 2.0 * (r * dmax).sqrt()).unwrap();
        let drive = |_t: f64| 0.0;
        let osc = Oscillator {
            mass: m,
            damping: 0.0,
            drive: &drive,
            axis: Axis::Normal { tangential: 0.0 },
            dt: tc / 4000.0,
            dt_min: tc / 4e6,
            max_jump: 0.05,
            force_scale: hertz_impact::max_force(e, r, m, v),
        };
        let (s, counts) = osc
            .run(&mut law, (-1e-3 * dmax, v), Stop::At(1.3 * tc), 1)
            .unwrap();
        let (t, v_in, v_out) = contact(&s);
        let peak = s.iter().map(|s| s.force).fold(0.0, f64::max);
        assert!((t / tc - 1.0).abs() < 1e-3, "t_c {t} against {tc}");
        assert!((peak / hertz_impact::max_force(e, r, m, v) - 1.0).abs() < 1e-3);
        assert!((-v_out / v_in - 1.0).abs() < 1e-4, "{v_in} {v_out}");
        assert_eq!(counts.trials, counts.accepted + counts.rejected + 1);
    }

    /// An adhesive sphere (JKR limit) on MRD's springs: the restitution against the
    /// closed form of `mrd::reference::adhesive_impact` (Hertz's loading, the flat
    /// punch's and JKR's unloading) within 1e-3 at 1.5 and 4 times the capture speed
    /// (2000 springs on the half line, t_c / 4000; measured 9e-5 and 2e-5), and capture
    /// below it:
    /// at 0.7 times the capture speed the sphere is still attached after 20 contact times.
    #[test]
    fn adhesive_impact_on_mrd_springs_and_its_capture() {
        use crate::adhesive::AdhesiveSprings;
        use mrd::reference::adhesive_impact as ai;
        let (e, r, w, m) = (1.0, 1.0, 1e-4, 1e-3);
        let profile = Profile::single(Shape::paraboloid(r).unwrap());
        let vc = ai::capture_speed(e, r, w, m);
        for (factor, want) in [(1.5, None), (4.0, None), (0.7, Some(0.0))] {
            let v = factor * vc;
            let dmax = hertz_impact::max_approach(e, r, m, v);
            let tc = hertz_impact::duration(e, r, m, v);
            let reach = (r * dmax).sqrt().max(ai::separation_radius(e, r, w));
            let mut law = AdhesiveSprings::body(&profile, e, w, 2000, 1.5 * reach).unwrap();
            let drive = |_t: f64| 0.0;
            let osc = Oscillator {
                mass: m,
                damping: 0.0,
                drive: &drive,
                axis: Axis::Normal { tangential: 0.0 },
                dt: tc / 4000.0,
                dt_min: tc / 4e6,
                max_jump: 0.05,
                force_scale: hertz_impact::max_force(e, r, m, v).max(ai::pull_off_scale(r, w)),
            };
            let touched = std::cell::Cell::new(false);
            let apart = |s: &Sample| {
                touched.set(touched.get() || s.contact_area > 0.0);
                touched.get() && s.contact_area == 0.0 && s.v < 0.0
            };
            let (samples, _) = osc
                .run(
                    &mut law,
                    (-1e-3 * dmax, v),
                    Stop::When {
                        until: &apart,
                        t_max: 20.0 * tc,
                    },
                    1,
                )
                .unwrap();
            let last = samples.last().unwrap();
            let closed = ai::restitution(e, r, w, m, v);
            match want {
                Some(_) => assert!(last.contact_area > 0.0, "{factor}: released at {}", last.t),
                None => {
                    let got = -last.v / v;
                    assert!(
                        closed > 0.0 && (got - closed).abs() < 1e-3,
                        "{factor}: {got} against {closed}"
                    );
                }
            }
        }
    }

    /// A rejected step leaves the law's history as it was: the same run with every
    /// step tried twice (a rollback, then the same trial again) gives the same bits.
    #[test]
    fn a_rollback_restores_the_state() {
        let profile = Profile::single(Shape::paraboloid(1.0).unwrap());
        let mut a = Springs::body(&profile, 1.0, 500, 0.3)
            .unwrap()
            .with_friction(0.8, 0.3)
            .unwrap();
        let mut b = a.clone();
        let motions: Vec<Motion> = (0..200)
            .map(|k| Motion {
                normal: 0.01,
                tangential: 1e-4 * (k as f64 * 0.1).sin(),
                dt: 1e-3,
            })
            .collect();
        for m in &motions {
            a.trial(*m).unwrap();
            a.commit().unwrap();
            b.trial(Motion {
                tangential: m.tangential * 3.0,
                ..*m
            })
            .unwrap();
            b.rollback();
            b.trial(*m).unwrap();
            b.commit().unwrap();
        }
        assert_eq!(a.committed(), b.committed());
        assert!(b.commit().is_err());
    }

    /// A harmonic force on a linear contact (a flat rough line: every spring in contact
    /// at any approach, F = k d), with a dashpot of damping ratio 0.05: after 60 periods
    /// the steady amplitude (the first harmonic fitted over three periods) is the damped
    /// linear oscillator's F1 / sqrt((k - m W^2)^2 + (c W)^2) within 2e-3 of the peak at
    /// W / w0 = 0.8, 1 and 1.2 and 200 steps per period (measured 7.4e-4, 2.8e-5 and
    /// less), and the error at resonance falls with the step at order 1.5 to 2.5
    /// (measured 2.2 from 50 to 100 steps per period).
    /// A normal wave out of range is refused by name, before any step.
    #[test]
    fn a_normal_wave_out_of_range_is_refused() {
        let profile = Profile::single(Shape::paraboloid(1.0).unwrap());
        let mut law = Springs::body(&profile, 1.0, 500, 0.3)
            .unwrap()
            .with_friction(0.8, 0.3)
            .unwrap();
        let drive = |_t: f64| 0.0;
        for (amplitude, omega, needle) in [
            (1.0, 1.0, "amplitude = 1"),
            (-0.1, 1.0, "amplitude = -0.1"),
            (0.2, f64::NAN, "omega = NaN"),
            (0.2, -1.0, "omega = -1"),
        ] {
            let osc = Oscillator {
                mass: 1.0,
                damping: 0.0,
                drive: &drive,
                axis: Axis::TangentialWave {
                    approach: 1e-3,
                    amplitude,
                    omega,
                    phase: 0.0,
                },
                dt: 0.1,
                dt_min: 0.01,
                max_jump: 0.05,
                force_scale: 1.0,
            };
            let e = osc
                .run(&mut law, (0.0, 0.0), Stop::At(1.0), 1)
                .unwrap_err()
                .to_string();
            assert!(e.contains(needle), "{e}");
        }
    }

    #[test]
    fn forced_linear_oscillator_against_its_closed_form() {
        let mut law = Springs::rough_line(&[0.0; 64], 1.0, 1.0, 1.0).unwrap();
        let (d0, m, zeta) = (0.01, 1.0, 0.05);
        let f = |law: &mut Springs, d: f64| {
            let f = law
                .trial(Motion {
                    normal: d,
                    tangential: 0.0,
                    dt: 1.0,
                })
                .unwrap()
                .normal;
            law.rollback();
            f
        };
        let f0 = f(&mut law, d0);
        let k = f0 / d0;
        assert!((f(&mut law, 2.0 * d0) / f0 - 2.0).abs() < 1e-12, "linear");
        let w0 = (k / m).sqrt();
        let c = 2.0 * zeta * m * w0;
        let f1 = 0.01 * f0;
        let error = |ratio: f64, steps: f64| {
            let w = ratio * w0;
            let drive = move |t: f64| f0 + f1 * (w * t).cos();
            let osc = Oscillator {
                mass: m,
                damping: c,
                drive: &drive,
                axis: Axis::Normal { tangential: 0.0 },
                dt: 2.0 * PI / w0 / steps,
                dt_min: 2.0 * PI / w0 / steps,
                max_jump: 1e300,
                force_scale: f0,
            };
            let period = 2.0 * PI / w;
            let (s, _) = osc
                .run(&mut law.clone(), (d0, 0.0), Stop::At(61.0 * period), 1)
                .unwrap();
            // The first harmonic: x = m + a cos(W t) + b sin(W t) fitted by least squares
            // over the last three periods.
            let basis = |t: f64| [1.0, (w * t).cos(), (w * t).sin()];
            let (mut g, mut r) = ([[0.0; 3]; 3], [0.0; 3]);
            for s in s.iter().filter(|s| s.t >= 58.0 * period) {
                let e = basis(s.t);
                for i in 0..3 {
                    r[i] += e[i] * s.x;
                    for j in 0..3 {
                        g[i][j] += e[i] * e[j];
                    }
                }
            }
            // Cramer's rule on the 3 x 3 normal equations.
            let det = |m: [[f64; 3]; 3]| {
                m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
                    - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                    + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
            };
            let column = |j: usize| {
                let mut m = g;
                (0..3).for_each(|i| m[i][j] = r[i]);
                det(m) / det(g)
            };
            let amplitude = column(1).hypot(column(2));
            let closed = f1 / ((k - m * w * w).powi(2) + (c * w).powi(2)).sqrt();
            let peak = f1 / (c * w0);
            (amplitude - closed).abs() / peak
        };
        for ratio in [0.8, 1.0, 1.2] {
            let e = error(ratio, 200.0);
            assert!(e < 2e-3, "W / w0 = {ratio}: {e}");
        }
        let order = (error(1.0, 50.0) / error(1.0, 100.0)).log2();
        assert!((1.5..2.5).contains(&order), "order {order}");
    }

    /// A viscoelastic impact in its elastic limits (closed forms): a relaxation time far
    /// beyond the contact time leaves the glassy modulus E_0 = E_inf + E_1, one far
    /// below it the relaxed E_inf; either way Hertz's contact time at that modulus and
    /// restitution 1 (the loss left at tau / t_c = 1e-5 or 1e4 is below 2e-4). MRD's
    /// viscoelastic springs within 1e-3, the 3D transient solve on 48^2 cells within 5e-3
    /// (its grid error, measured 1.0e-3 and 5.6e-4 on the contact time).
    #[test]
    fn viscoelastic_impact_in_its_elastic_limits() {
        use crate::viscoelastic::{ViscoelasticBem3d, ViscoelasticSprings};
        let (r, m, v, e_inf, e1) = (1.0, 1e-3, 0.01, 1.0, 3.0);
        let profile = Profile::single(Shape::paraboloid(r).unwrap());
        let wide = (r * hertz_impact::max_approach(e_inf, r, m, v)).sqrt();
        for (tau_over_tc, e_lim) in [(1e4, e_inf + e1), (1e-5, e_inf)] {
            let tc = hertz_impact::duration(e_lim, r, m, v);
            let tau = tau_over_tc * tc;
            let drive = |_t: f64| 0.0;
            let osc = |steps: f64| Oscillator {
                mass: m,
                damping: 0.0,
                drive: &drive,
                axis: Axis::Normal { tangential: 0.0 },
                dt: tc / steps,
                dt_min: tc / (1000.0 * steps),
                max_jump: 0.05,
                force_scale: hertz_impact::max_force(e_lim, r, m, v),
            };
            let start = (-1e-3 * hertz_impact::max_approach(e_lim, r, m, v), v);
            let prony = mrd::rheology::Prony::new(e_inf, vec![(e1, tau)]).unwrap();
            let mut law = ViscoelasticSprings::body(&profile, &prony, 4000, 1.5 * wide).unwrap();
            let (s, _) = osc(2000.0)
                .run(&mut law, start, Stop::At(1.3 * tc), 1)
                .unwrap();
            let (t, v_in, v_out) = contact(&s);
            assert!(
                (t / tc - 1.0).abs() < 1e-3,
                "MRD, tau/tc {tau_over_tc}: t_c {t} against {tc}"
            );
            assert!(
                (-v_out / v_in - 1.0).abs() < 1e-3,
                "MRD, tau/tc {tau_over_tc}: e = {}",
                -v_out / v_in
            );
            let n = 48;
            let side = 2.6 * wide;
            let h = side / n as f64;
            let z: Vec<f64> = (0..n * n)
                .map(|k| {
                    let (x, y) = (
                        ((k % n) as f64 + 0.5) * h - side / 2.0,
                        ((k / n) as f64 + 0.5) * h - side / 2.0,
                    );
                    -(x * x + y * y) / (2.0 * r)
                })
                .collect();
            let op = bem3d::NonPeriodicHalfSpace::new(n, n, side, side, 1.0);
            let modulus = bem3d::viscoelastic::Relaxation::new(e_inf, vec![(e1, tau)]).unwrap();
            let mut law = ViscoelasticBem3d::new(op, &z, None, modulus, 1e-8, 10_000).unwrap();
            let (s, _) = osc(200.0)
                .run(&mut law, start, Stop::At(1.3 * tc), 1)
                .unwrap();
            let (t, v_in, v_out) = contact(&s);
            assert!(
                (t / tc - 1.0).abs() < 5e-3,
                "3D, tau/tc {tau_over_tc}: t_c {t} against {tc}"
            );
            assert!(
                (-v_out / v_in - 1.0).abs() < 5e-3,
                "3D, tau/tc {tau_over_tc}: e = {}",
                -v_out / v_in
            );
        }
    }

    /// The viscoelastic laws take a rejected step back: the same history with every step
    /// first tried at another approach and rolled back gives the same bits, MRD and 3D.
    #[test]
    fn viscoelastic_rollbacks_restore_the_state() {
        use crate::law::Forces;
        use crate::viscoelastic::{ViscoelasticBem3d, ViscoelasticSprings};
        let profile = Profile::single(Shape::paraboloid(1.0).unwrap());
        let prony = mrd::rheology::Prony::new(1.0, vec![(3.0, 0.5)]).unwrap();
        let n = 24;
        let side = 0.4;
        let h = side / n as f64;
        let z: Vec<f64> = (0..n * n)
            .map(|k| {
                let x = ((k % n) as f64 + 0.5) * h - side / 2.0;
                let y = ((k / n) as f64 + 0.5) * h - side / 2.0;
                -(x * x + y * y) / 2.0
            })
            .collect();
        let three = || {
            let op = bem3d::NonPeriodicHalfSpace::new(n, n, side, side, 1.0);
            let modulus = bem3d::viscoelastic::Relaxation::new(1.0, vec![(3.0, 0.5)]).unwrap();
            ViscoelasticBem3d::new(op, &z, None, modulus, 1e-10, 10_000).unwrap()
        };
        let mrd = || ViscoelasticSprings::body(&profile, &prony, 400, 0.2).unwrap();
        let laws: [(Box<dyn ContactLaw>, Box<dyn ContactLaw>); 2] = [
            (Box::new(mrd()), Box::new(mrd())),
            (Box::new(three()), Box::new(three())),
        ];
        for (mut a, mut b) in laws {
            // In, out and in again, apart in between.
            for k in 0..40 {
                let normal = 4e-3 * (k as f64 * 0.2).sin();
                let m = Motion {
                    normal,
                    tangential: 0.0,
                    dt: 0.05,
                };
                let fa = a.trial(m).unwrap();
                a.commit().unwrap();
                b.trial(Motion {
                    normal: 2.0 * normal + 1e-3,
                    ..m
                })
                .unwrap();
                b.rollback();
                let fb = b.trial(m).unwrap();
                b.commit().unwrap();
                // (The stiffness is NaN in both: these laws do not compute it.)
                let bits = |f: Forces| (f.normal.to_bits(), f.contact_area.to_bits(), f.iterations);
                assert_eq!(bits(fa), bits(fb), "{}: step {k}", a.describe());
            }
            assert!(b.commit().is_err());
            assert!(a.approach_at(1e-5).unwrap() > 0.0);
        }
    }
}
