//! Viscoelastic normal contact on the MRD foundation (Section 8, Eqs. 62-63).
//!
//! Each spring carries `f(t) = dx Int_{-inf}^t E*(t - t') du/dt' dt'` (Eq. 63 with
//! E*(t) = 4 G(t) for an incompressible medium), u = d(t) - z1d(x) while in contact. The
//! relaxation modulus is a Prony series `E*(t) = E_inf + sum_i E_i exp(-t/tau_i)`, whose
//! hereditary integrals are updated recursively, exactly for piecewise-linear u(t).
//! During monotonic indentation the contact radius never shrinks and the result equals
//! Radok's (1957) solution `F(t) = Int_0^t E*(t - s) dF_el/ds ds / E*` built on the
//! elastic force-depth law, which [`radok_force`] evaluates by quadrature.

use crate::error::{positive, MrdError, Result};
use crate::profile::Profile;

pub use crate::rheology::Prony;

/// Time-steps the spring row under a prescribed depth history `depth(t)` sampled at
/// `times` (increasing, from 0 with depth 0), with `n_half` springs on [0, half_length]
/// (mirrored). Returns the force at each time. Springs follow the profile while
/// `d > g_i`, so a decreasing depth may leave them in tension: for unloading use
/// [`SpringRow`], whose springs separate at zero force.
pub fn simulate(
    profile: &Profile,
    modulus: &Prony,
    depth: &dyn Fn(f64) -> f64,
    times: &[f64],
    n_half: usize,
    half_length: f64,
) -> Result<Vec<f64>> {
    positive("half_length", half_length)?;
    if n_half < 2 || times.len() < 2 || times.windows(2).any(|w| w[1] <= w[0]) {
        return Err(MrdError::InvalidParameter {
            name: "times",
            value: times.len() as f64,
            reason: "need >= 2 increasing times and >= 2 springs",
        });
    }
    let (l, dx, gaps) = crate::foundation::half_line(profile, n_half, half_length)?;
    let m = modulus.terms.len();
    // Per spring: current u and one hereditary variable per Prony term.
    let mut u = vec![0.0f64; n_half];
    let mut h = vec![0.0f64; n_half * m];
    let mut out = Vec::with_capacity(times.len());
    let force = |u: &[f64], h: &[f64]| -> f64 {
        let mut f = 0.0;
        for i in 0..n_half {
            f += modulus.relaxed * u[i]
                + (0..m)
                    .map(|k| modulus.terms[k].0 * h[i * m + k])
                    .sum::<f64>();
        }
        2.0 * dx * f
    };
    out.push(force(&u, &h));
    for w in times.windows(2) {
        let dt = w[1] - w[0];
        let d = depth(w[1]);
        let decay: Vec<(f64, f64)> = modulus
            .terms
            .iter()
            .map(|&(_, tau)| {
                let a = (-dt / tau).exp();
                (a, tau / dt * (1.0 - a)) // exact for u linear over the step
            })
            .collect();
        for i in 0..n_half {
            let u_new = (d - gaps[i]).max(0.0);
            let du = u_new - u[i];
            for (k, &(a, b)) in decay.iter().enumerate() {
                h[i * m + k] = a * h[i * m + k] + b * du;
            }
            u[i] = u_new;
        }
        if u.last().is_some_and(|&v| v > 0.0) && profile.rim().is_none() {
            return Err(MrdError::OutOfRange {
                needed: f64::INFINITY,
                limit: l,
            });
        }
        out.push(force(&u, &h));
    }
    Ok(out)
}

/// A row of viscoelastic springs under a rigid profile that may lose contact (Eq. 63
/// with unilateral contact): spring i, of gap g_i, carries
/// `f_i = dx Int E*(t - t') du_i/dt' dt' >= 0`; in contact u_i = d - g_i, out of it
/// f_i = 0 and u_i recovers freely (creep recovery), its gap `u_i + g_i - d >= 0`.
/// Hereditary integrals as in [`simulate`] (exact for u_i piecewise linear in time):
/// over a step, `f_i = dx (E_eff u_i + H_i)` with `E_eff = E_inf + sum_k E_k b_k` and
/// `H_i` the history, so each spring's state is a closed-form choice: contact when its
/// force at u_i = d - g_i is >= 0, else u_i = -H_i / E_eff. Under force control the total
/// force `E_eff dx sum_i (d - d_i)+` with thresholds `d_i = g_i - H_i / E_eff` is inverted
/// exactly (the elastic foundation's sort and prefix sums). During monotonic indentation
/// no spring separates and the row is [`simulate`]'s; on unloading springs separate when
/// their force reaches zero (Ting's problem in one dimension).
#[derive(Debug, Clone)]
pub struct SpringRow {
    gaps: Vec<f64>,
    dx: f64,
    modulus: Prony,
    u: Vec<f64>,
    /// h[i * m + k]: spring i, Prony term k.
    h: Vec<f64>,
    time: f64,
}

/// The load at the end of a step of a [`SpringRow`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RowLoad {
    Depth(f64),
    Force(f64),
}

/// The state of a [`SpringRow`] after a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RowState {
    pub time: f64,
    pub depth: f64,
    pub force: f64,
    /// Springs in contact.
    pub contacts: usize,
}

impl SpringRow {
    /// Springs of width `dx` with gaps `gaps` (finite), undeformed at t = 0.
    pub fn new(gaps: &[f64], dx: f64, modulus: &Prony) -> Result<Self> {
        positive("dx", dx)?;
        if gaps.is_empty() || gaps.iter().any(|g| !g.is_finite()) {
            return Err(MrdError::InvalidData(
                "a spring row needs at least one spring and finite gaps".into(),
            ));
        }
        Ok(Self {
            gaps: gaps.to_vec(),
            dx,
            modulus: modulus.clone(),
            u: vec![0.0; gaps.len()],
            h: vec![0.0; gaps.len() * modulus.terms.len()],
            time: 0.0,
        })
    }

    pub fn time(&self) -> f64 {
        self.time
    }

    /// Spring displacements u_i.
    pub fn displacement(&self) -> &[f64] {
        &self.u
    }

    /// Advances by `dt` to `load` (depth from the profile's reference, or total force).
    pub fn step(&mut self, dt: f64, load: RowLoad) -> Result<RowState> {
        positive("time step", dt)?;
        let m = self.modulus.terms.len();
        let (ab, e_eff) = self.modulus.step_factors(dt);
        // H_i / E_eff: the displacement the history holds at zero force.
        let free: Vec<f64> = (0..self.gaps.len())
            .map(|i| {
                -(0..m)
                    .map(|k| {
                        let (a, b) = ab[k];
                        self.modulus.terms[k].0 * (a * self.h[i * m + k] - b * self.u[i])
                    })
                    .sum::<f64>()
                    / e_eff
            })
            .collect();
        // Spring i touches from d > g_i + free_i on.
        let thresholds: Vec<f64> = self.gaps.iter().zip(&free).map(|(g, f)| g + f).collect();
        let depth = match load {
            RowLoad::Depth(d) => {
                if !d.is_finite() {
                    return Err(MrdError::InvalidParameter {
                        name: "depth",
                        value: d,
                        reason: "must be finite",
                    });
                }
                d
            }
            RowLoad::Force(f) => {
                crate::error::non_negative("force", f)?;
                let low = thresholds.iter().cloned().fold(f64::INFINITY, f64::min);
                let shifted: Vec<f64> = thresholds.iter().map(|t| t - low).collect();
                let row = crate::foundation::Foundation::new(&shifted, self.dx, e_eff)?;
                row.at_force(f)?.depth + low
            }
        };
        let mut force = 0.0;
        let mut contacts = 0;
        for i in 0..self.gaps.len() {
            let u_new = if depth > thresholds[i] {
                contacts += 1;
                force += e_eff * (depth - thresholds[i]);
                depth - self.gaps[i]
            } else {
                free[i]
            };
            let du = u_new - self.u[i];
            for (h, &(a, b)) in self.h[i * m..(i + 1) * m].iter_mut().zip(&ab) {
                *h = a * *h + b * du;
            }
            self.u[i] = u_new;
        }
        self.time += dt;
        Ok(RowState {
            time: self.time,
            depth,
            force: force * self.dx,
            contacts,
        })
    }
}

/// Tangential viscoelastic springs under a held normal load (Eqs. 64-65): spring i
/// carries `f_i = dx Int G*(t - t') dw_i/dt' dt'` with w_i its tangential elongation and
/// G*(t) the tangential modulus (8/3 G(t) for an incompressible elastomer, Eq. 65). While
/// it sticks, its top moves with the indenter (w_i grows by the indenter's tangential
/// step); when |f_i| would exceed mu times its normal force it slips, carrying
/// `sign(f_i) mu f_z,i`; a spring without normal force relaxes freely (f_i = 0). Hereditary
/// integrals as in [`SpringRow`] (exact for w_i piecewise linear in time), so each step
/// is a closed-form choice per spring. With a constant modulus this is the MRD
/// Cattaneo-Mindlin contact of [`crate::tangential`] (Eqs. 41-50).
#[derive(Debug, Clone)]
pub struct TangentialRow {
    normal: Vec<f64>,
    dx: f64,
    mu: f64,
    modulus: Prony,
    w: Vec<f64>,
    h: Vec<f64>,
    displacement: f64,
    time: f64,
}

/// The state of a [`TangentialRow`] after a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TangentialRowState {
    pub time: f64,
    /// Tangential displacement of the indenter.
    pub displacement: f64,
    pub force: f64,
    /// Loaded springs that stick.
    pub sticking: usize,
    /// Friction work of the step, sum over slipping springs of f_i (du - dw_i) with f_i
    /// at the step's end (the slip direction does not change within a step).
    pub slip_work: f64,
    /// The outermost sticking spring's index (None: nothing sticks).
    pub stick_edge: Option<usize>,
}

impl TangentialRow {
    /// Springs of width `dx` with normal forces `normal` (>= 0, held), friction
    /// coefficient `mu`, tangential modulus `modulus` (G*(t)); undeformed at t = 0.
    pub fn new(normal: &[f64], dx: f64, mu: f64, modulus: &Prony) -> Result<Self> {
        positive("dx", dx)?;
        positive("friction coefficient", mu)?;
        if normal.is_empty() || normal.iter().any(|f| !(f.is_finite() && *f >= 0.0)) {
            return Err(MrdError::InvalidData(
                "tangential springs need at least one spring and finite normal forces >= 0".into(),
            ));
        }
        Ok(Self {
            normal: normal.to_vec(),
            dx,
            mu,
            modulus: modulus.clone(),
            w: vec![0.0; normal.len()],
            h: vec![0.0; normal.len() * modulus.terms.len()],
            displacement: 0.0,
            time: 0.0,
        })
    }

    /// Advances by `dt` with the indenter at tangential displacement `ux` at its end.
    pub fn step(&mut self, dt: f64, ux: f64) -> Result<TangentialRowState> {
        positive("time step", dt)?;
        if !ux.is_finite() {
            return Err(MrdError::InvalidParameter {
                name: "tangential displacement",
                value: ux,
                reason: "must be finite",
            });
        }
        let m = self.modulus.terms.len();
        let (ab, g_eff) = self.modulus.step_factors(dt);
        let du = ux - self.displacement;
        let (mut force, mut sticking, mut slip_work) = (0.0, 0usize, 0.0);
        let mut stick_edge = None;
        for i in 0..self.normal.len() {
            let hist = &mut self.h[i * m..(i + 1) * m];
            // f / dx = g_eff w_new + history.
            let history: f64 = self
                .modulus
                .terms
                .iter()
                .zip(hist.iter())
                .zip(&ab)
                .map(|((t, h), &(a, b))| t.0 * (a * h - b * self.w[i]))
                .sum();
            let limit = self.mu * self.normal[i] / self.dx;
            let trial = g_eff * (self.w[i] + du) + history;
            let (w_new, f) = if self.normal[i] > 0.0 && trial.abs() <= limit {
                sticking += 1;
                stick_edge = Some(i);
                (self.w[i] + du, trial)
            } else {
                let f = limit * trial.signum();
                ((f - history) / g_eff, f)
            };
            let dw = w_new - self.w[i];
            slip_work += f * self.dx * (du - dw);
            for (h, &(a, b)) in hist.iter_mut().zip(&ab) {
                *h = a * *h + b * dw;
            }
            self.w[i] = w_new;
            force += f * self.dx;
        }
        self.displacement = ux;
        self.time += dt;
        Ok(TangentialRowState {
            time: self.time,
            displacement: ux,
            force,
            sticking,
            slip_work,
            stick_edge,
        })
    }

    /// Energy stored in the springs, dx sum_i (G_inf w_i^2 + sum_k G_k h_ik^2) / 2 (the
    /// Maxwell branch k's spring is stretched by h_ik).
    pub fn stored_energy(&self) -> f64 {
        let m = self.modulus.terms.len();
        let mut e = 0.0;
        for i in 0..self.w.len() {
            e += self.modulus.relaxed * self.w[i] * self.w[i];
            for (k, t) in self.modulus.terms.iter().enumerate() {
                e += t.0 * self.h[i * m + k].powi(2);
            }
        }
        0.5 * self.dx * e
    }

    /// Power dissipated in the dashpots, dx sum_i sum_k (G_k / tau_k) h_ik^2.
    pub fn viscous_power(&self) -> f64 {
        let m = self.modulus.terms.len();
        let mut p = 0.0;
        for i in 0..self.w.len() {
            for (k, t) in self.modulus.terms.iter().enumerate() {
                p += t.0 / t.1 * self.h[i * m + k].powi(2);
            }
        }
        self.dx * p
    }
}

/// Radok's solution for monotonic indentation: `F(t) = Int_0^t E*(t - s) dPhi(d(s))/ds ds`
/// with Phi(d) = F_el(d)/E* the elastic force-depth law at unit modulus, by quadrature
/// (d' from the given derivative; `breaks` are times where d' jumps).
pub fn radok_force(
    profile: &Profile,
    modulus: &Prony,
    depth: &dyn Fn(f64) -> f64,
    depth_rate: &dyn Fn(f64) -> f64,
    breaks: &[f64],
    t: f64,
) -> Result<f64> {
    let unit = crate::normal::AxisymmetricContact::new(profile.clone(), 1.0)?;
    // dPhi/ds = dF/dd (unit modulus) * d'(s) = 2 a(d(s)) d'(s)   (Eq. 20)
    let integrand = |s: f64| -> f64 {
        let a = unit
            .state_at_depth(depth(s).max(0.0))
            .map(|st| st.radius)
            .unwrap_or(f64::NAN);
        modulus.at(t - s) * 2.0 * a * depth_rate(s)
    };
    crate::numerics::quad::tanh_sinh_split(integrand, 0.0, t, breaks, 1e-11)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::profile::Shape;

    #[test]
    fn ramp_into_standard_linear_solid_matches_radok() {
        // Sphere R = 1, d = v t, E*(t) = 1 + 4 exp(-t/0.5), t in [0, 2].
        let p = Profile::single(Shape::paraboloid(1.0).unwrap());
        let g = Prony::new(1.0, vec![(4.0, 0.5)]).unwrap();
        let v = 0.05;
        let times: Vec<f64> = (0..=400).map(|k| 2.0 * k as f64 / 400.0).collect();
        let f = simulate(&p, &g, &|t| v * t, &times, 20_000, 0.5).unwrap();
        for &k in &[100usize, 200, 400] {
            let exact = radok_force(&p, &g, &|t| v * t, &|_| v, &[], times[k]).unwrap();
            // Stated tolerance: 2e-3 at 20000 springs and 400 steps.
            assert!(
                (f[k] / exact - 1.0).abs() < 2e-3,
                "t = {}: {} vs {exact}",
                times[k],
                f[k]
            );
        }
        // Limits: a purely elastic modulus gives Hertz.
        let el = Prony::new(3.0, vec![]).unwrap();
        let fe = simulate(&p, &el, &|t| v * t, &times, 20_000, 0.5).unwrap();
        let hertz = crate::reference::hertz::force(3.0, 1.0, 0.1);
        assert!((fe[400] / hertz - 1.0).abs() < 1e-3);
    }

    #[test]
    fn relaxation_at_fixed_depth() {
        // Step to d0 then hold: F(t) = E*(t) Phi(d0) for the flat punch (contact fixed).
        let p = Profile::flat_punch(0.5).unwrap();
        let g = Prony::new(1.0, vec![(2.0, 1.0)]).unwrap();
        let times: Vec<f64> = (0..=1000).map(|k| 5.0 * k as f64 / 1000.0).collect();
        let d0 = 0.01;
        let ramp = 0.005; // reach d0 linearly in one step of 0.005
        let f = simulate(
            &p,
            &g,
            &|t| if t < ramp { d0 * t / ramp } else { d0 },
            &times,
            100,
            0.5,
        )
        .unwrap();
        let at = |t: f64| {
            // Radok for a linear ramp then hold on a flat punch (Phi = 2 a d).
            let rate = d0 / ramp;
            let s1 = t.min(ramp);
            2.0 * 0.5 * rate * (1.0 * s1 + 2.0 * 1.0 * ((-(t - s1)).exp() - (-t).exp()))
        };
        for &k in &[1usize, 10, 200, 1000] {
            assert!((f[k] / at(times[k]) - 1.0).abs() < 1e-9, "t = {}", times[k]);
        }
        assert!(Prony::new(-1.0, vec![]).is_err());
        assert!(Prony::new(1.0, vec![(1.0, 0.0)]).is_err());
    }

    #[test]
    fn spring_row_loading_is_simulate_and_unloading_separates_as_the_closed_form() {
        // Monotonic indentation: the row and [`simulate`] agree.
        let p = Profile::single(Shape::paraboloid(1.0).unwrap());
        let g = Prony::new(1.0, vec![(4.0, 0.5), (1.0, 0.05)]).unwrap();
        let times: Vec<f64> = (0..=200).map(|k| k as f64 / 100.0).collect();
        let depth = |t: f64| 0.05 * t;
        let f = simulate(&p, &g, &depth, &times, 2000, 0.5).unwrap();
        let (_, dx, gaps) = crate::foundation::half_line(&p, 2000, 0.5).unwrap();
        let mut row = SpringRow::new(&gaps, dx, &g).unwrap();
        for k in 1..times.len() {
            let s = row.step(0.01, RowLoad::Depth(depth(times[k]))).unwrap();
            assert!(
                (2.0 * s.force / f[k] - 1.0).abs() < 1e-12,
                "t = {}",
                times[k]
            );
        }
        // One spring (unit width, gap 0), standard linear solid E* = 1 + 4 exp(-t/0.5):
        // u = t up to t = 1, then the indenter retreats at the same speed. The force
        // F = u + 4 h, h = Int exp(-(t - s)/tau) du(s), reaches 0 at t_d (bisection);
        // afterwards the spring recovers freely, u = u(t_d) exp(-(t - t_d)/tau_r),
        // tau_r = tau E*(0)/E_inf = 2.5.
        let (e1, tau) = (4.0, 0.5);
        let sls = Prony::new(1.0, vec![(e1, tau)]).unwrap();
        let u = |t: f64| if t <= 1.0 { t } else { 2.0 - t };
        let h = |t: f64| {
            if t <= 1.0 {
                tau * (1.0 - (-t / tau).exp())
            } else {
                let h1 = tau * (1.0 - (-1.0 / tau).exp());
                h1 * (-(t - 1.0) / tau).exp() - tau * (1.0 - (-(t - 1.0) / tau).exp())
            }
        };
        let force = |t: f64| u(t) + e1 * h(t);
        let (mut lo, mut hi) = (1.0, 2.0);
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if force(mid) > 0.0 {
                lo = mid
            } else {
                hi = mid
            }
        }
        let t_d = lo;
        assert!(t_d > 1.0 && t_d < 2.0);
        let dt = 1e-3;
        let mut one = SpringRow::new(&[0.0], 1.0, &sls).unwrap();
        let mut separated_at = None;
        for k in 1..=4000 {
            let t = k as f64 * dt;
            let s = one.step(dt, RowLoad::Depth(u(t))).unwrap();
            if s.contacts == 1 {
                // Exact while in contact (u piecewise linear, kink on a step).
                assert!((s.force - force(t)).abs() < 1e-9, "t = {t}");
            } else {
                assert_eq!(s.force, 0.0);
                separated_at.get_or_insert(t);
            }
        }
        let t_sep = separated_at.expect("the spring separates");
        assert!((t_sep - t_d).abs() <= dt, "{t_sep} vs {t_d}");
        let exact = u(t_d) * (-(4.0 - t_d) / (tau * 5.0)).exp();
        let got = one.displacement()[0];
        assert!((got / exact - 1.0).abs() < 1e-2, "{got} vs {exact}");
    }

    #[test]
    fn spring_row_under_force_control_holds_the_force_and_creeps() {
        let gaps: Vec<f64> = (0..500).map(|i| ((i * 7919) % 500) as f64 * 1e-4).collect();
        let dx = 1.0 / 500.0;
        // Constant modulus: the elastic foundation.
        let el = Prony::new(2.0, vec![]).unwrap();
        let mut row = SpringRow::new(&gaps, dx, &el).unwrap();
        let found = crate::foundation::Foundation::new(&gaps, dx, 2.0).unwrap();
        for f in [1e-5, 1e-4, 3e-5] {
            let s = row.step(0.1, RowLoad::Force(f)).unwrap();
            let e = found.at_force(f).unwrap();
            assert!((s.depth - e.depth).abs() < 1e-12 && s.contacts == e.contacts);
        }
        // A held force creeps: the depth grows, the force stays, contact grows.
        let g = Prony::new(1.0, vec![(4.0, 0.5)]).unwrap();
        let mut row = SpringRow::new(&gaps, dx, &g).unwrap();
        let mut last = row.step(0.01, RowLoad::Force(1e-4)).unwrap();
        for _ in 0..600 {
            let s = row.step(0.05, RowLoad::Force(1e-4)).unwrap();
            assert!((s.force / 1e-4 - 1.0).abs() < 1e-12);
            assert!(s.depth > last.depth && s.contacts >= last.contacts);
            last = s;
        }
        // Long-time limit (30 s, 12 retardation times tau E*(0)/E_inf): the relaxed
        // foundation's depth.
        let relaxed = crate::foundation::Foundation::new(&gaps, dx, 1.0)
            .unwrap()
            .at_force(1e-4)
            .unwrap();
        assert!(
            (last.depth / relaxed.depth - 1.0).abs() < 1e-3,
            "{} vs {}",
            last.depth,
            relaxed.depth
        );
        assert!(row.step(0.0, RowLoad::Force(1e-4)).is_err());
        assert!(row.step(0.1, RowLoad::Force(-1.0)).is_err());
        assert!(row.step(0.1, RowLoad::Depth(f64::NAN)).is_err());
        assert!(SpringRow::new(&[], 1.0, &g).is_err());
        assert!(SpringRow::new(&[f64::INFINITY], 1.0, &g).is_err());
    }

    #[test]
    fn spring_row_contact_does_not_shrink_after_a_load_decrease() {
        // Li, Brenner & Frerot (arXiv 2511.19402, 2025): for any linear viscoelastic
        // medium the contact area cannot decrease while a reduced load is held.
        let gaps: Vec<f64> = (0..2000)
            .map(|i| (0.37 * i as f64).sin().abs() * 1e-3 + (i % 13) as f64 * 1e-5)
            .collect();
        let g = Prony::new(1.0, vec![(3.0, 0.2), (2.0, 2.0)]).unwrap();
        let mut row = SpringRow::new(&gaps, 1.0 / 2000.0, &g).unwrap();
        for _ in 0..30 {
            row.step(0.05, RowLoad::Force(2e-4)).unwrap();
        }
        let contacts: Vec<usize> = (0..80)
            .map(|_| row.step(0.05, RowLoad::Force(5e-5)).unwrap().contacts)
            .collect();
        for w in contacts.windows(2) {
            assert!(w[1] >= w[0], "{contacts:?}");
        }
        assert!(contacts[79] > contacts[0], "{contacts:?}");
    }

    #[test]
    fn tangential_row_sticks_as_the_closed_form_and_slips_as_cattaneo_mindlin() {
        // No slip (mu huge), 100 loaded springs of unit width: a tangential ramp
        // u = 0.01 t to t = 1, then held: F = 100 (G_inf u + G1 Int exp(-(t-s)/tau) du),
        // exact for piecewise-linear u.
        let (g_inf, g1, tau) = (1.0, 3.0, 0.4);
        let g = Prony::new(g_inf, vec![(g1, tau)]).unwrap();
        let mut row = TangentialRow::new(&[1.0; 100], 1.0, 1e12, &g).unwrap();
        let v = 0.01;
        for k in 1..=300 {
            let t = k as f64 * 0.01;
            let s = row.step(0.01, v * t.min(1.0)).unwrap();
            let h = if t <= 1.0 {
                v * tau * (1.0 - (-t / tau).exp())
            } else {
                v * tau * (1.0 - (-1.0 / tau).exp()) * (-(t - 1.0) / tau).exp()
            };
            let exact = 100.0 * (g_inf * v * t.min(1.0) + g1 * h);
            assert!((s.force / exact - 1.0).abs() < 1e-12, "t = {t}");
            assert_eq!(s.sticking, 100);
        }
        // Constant modulus: Cattaneo-Mindlin of the sphere on springs against the closed
        // form (`crate::tangential`, Eqs. 41-50) along a monotonic tangential loading.
        let p = Profile::single(Shape::paraboloid(1.0).unwrap());
        let (e_star, g_star, mu, f_n) = (1.0, 0.8, 0.3, 1e-3);
        let contact = crate::normal::AxisymmetricContact::new(p.clone(), e_star).unwrap();
        let cm = crate::tangential::TangentialContact::new(contact, g_star, mu, f_n).unwrap();
        let d = cm.normal.depth;
        let (_, dx, gaps) = crate::foundation::half_line(&p, 20_000, 0.1).unwrap();
        let normal: Vec<f64> = gaps
            .iter()
            .map(|g| e_star * dx * (d - g).max(0.0))
            .collect();
        let mut row =
            TangentialRow::new(&normal, dx, mu, &Prony::new(g_star, vec![]).unwrap()).unwrap();
        let umax = cm.max_displacement();
        for k in 1..=20 {
            let ux = umax * k as f64 / 20.0 * 0.999;
            let s = row.step(1.0, ux).unwrap();
            let exact = cm.at_displacement(ux).unwrap().force;
            // The half line stands for both halves: twice its force. Stated tolerance:
            // 1e-8 at 20000 springs on the half line (measured 3e-10); the stick zone
            // shrinks from 89 % to 3 % of the loaded springs.
            assert!(
                (2.0 * s.force / exact - 1.0).abs() < 1e-8,
                "{ux}: {} vs {exact}",
                2.0 * s.force
            );
        }
        assert!(TangentialRow::new(&[-1.0], 1.0, 0.3, &g).is_err());
        assert!(TangentialRow::new(&[1.0], 1.0, 0.0, &g).is_err());
        assert!(row.step(1.0, f64::NAN).is_err());
    }
}
