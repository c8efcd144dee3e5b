//! The discretised 1D elastic foundation: N independent springs of stiffness
//! `E* dx` (Eq. 3) under a rigid profile with gaps g_i.
//!
//! At approach d, spring i carries `E* dx (d - g_i)` when `d > g_i`. After one sort of
//! the gaps and a prefix sum, the force `F(d) = E* dx (m d - S_m)` (m springs in contact,
//! S_m the sum of their gaps) is exact in O(log N), and a force-controlled solve is an
//! exact inversion of this piecewise-linear function, not an iteration.

use crate::error::{non_negative, positive, MrdError, Result};
use crate::profile::Profile;

/// The mirrored half-line of an axisymmetric contact on the foundation: `n_half` springs
/// at the midpoints of [0, L], L the profile's rim if it has one, else `half_length`.
/// Returns (L, dx, gaps z1d(x_i)); each spring stands for itself and its mirror image.
/// A line longer than a tabulated profile's range is an error (no extrapolation).
pub fn half_line(
    profile: &Profile,
    n_half: usize,
    half_length: f64,
) -> Result<(f64, f64, Vec<f64>)> {
    let l = line_extent(profile, half_length)?;
    let dx = l / n_half.max(1) as f64;
    let gaps = (0..n_half)
        .map(|i| profile.z1d((i as f64 + 0.5) * dx))
        .collect();
    Ok((l, dx, gaps))
}

/// Half-length of a spring line under `profile`: its rim, else `half_length` (> 0);
/// beyond the range of a tabulated profile is an error.
pub fn line_extent(profile: &Profile, half_length: f64) -> Result<f64> {
    let l = match profile.rim() {
        Some(r) => r,
        None => positive("half_length", half_length)?,
    };
    if l > profile.max_contact_radius() * (1.0 + 1e-12) {
        return Err(MrdError::OutOfRange {
            needed: l,
            limit: profile.max_contact_radius(),
        });
    }
    Ok(l)
}

/// A spring row with sorted gaps and prefix sums.
#[derive(Debug, Clone)]
pub struct Foundation {
    dx: f64,
    modulus: f64,
    sorted: Vec<f64>,
    /// prefix[m] = sum of the m smallest gaps (prefix[0] = 0).
    prefix: Vec<f64>,
}

/// One solved state of the spring row.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FoundationState {
    pub depth: f64,
    pub force: f64,
    /// Number of springs in contact.
    pub contacts: usize,
    /// Incremental stiffness dF/dd = E* dx m.
    pub stiffness: f64,
}

impl Foundation {
    /// Springs with gaps `gaps` (any order, finite), spacing `dx`, modulus E*.
    pub fn new(gaps: &[f64], dx: f64, modulus: f64) -> Result<Self> {
        positive("dx", dx)?;
        positive("e_star", modulus)?;
        if gaps.is_empty() {
            return Err(MrdError::InvalidData(
                "foundation needs at least one spring".into(),
            ));
        }
        if let Some((i, what)) = crate::error::bad_height(gaps) {
            return Err(MrdError::InvalidData(format!("{what} at index {i}")));
        }
        let mut sorted = gaps.to_vec();
        sorted.sort_unstable_by(f64::total_cmp);
        let mut prefix = Vec::with_capacity(sorted.len() + 1);
        let mut acc = 0.0;
        prefix.push(0.0);
        for &g in &sorted {
            acc += g;
            prefix.push(acc);
        }
        Ok(Self {
            dx,
            modulus,
            sorted,
            prefix,
        })
    }

    pub fn len(&self) -> usize {
        self.sorted.len()
    }
    pub fn is_empty(&self) -> bool {
        self.sorted.is_empty()
    }
    pub fn dx(&self) -> f64 {
        self.dx
    }
    /// Smallest gap: the first contact happens at d = min gap.
    pub fn first_contact(&self) -> f64 {
        self.sorted[0]
    }
    /// Largest gap: complete contact from d = max gap on.
    pub fn full_contact(&self) -> f64 {
        *self.sorted.last().unwrap()
    }

    fn state_with(&self, d: f64, m: usize) -> FoundationState {
        let k = self.modulus * self.dx;
        FoundationState {
            depth: d,
            force: k * (m as f64 * d - self.prefix[m]),
            contacts: m,
            stiffness: k * m as f64,
        }
    }

    /// Exact state at approach `d` (O(log N)).
    pub fn at_depth(&self, d: f64) -> Result<FoundationState> {
        if !d.is_finite() {
            return Err(MrdError::InvalidParameter {
                name: "depth",
                value: d,
                reason: "must be finite",
            });
        }
        let m = self.sorted.partition_point(|&g| g <= d);
        Ok(self.state_with(d, m))
    }

    /// Exact force-controlled state (O(log N)): d with F(d) = f.
    pub fn at_force(&self, f: f64) -> Result<FoundationState> {
        non_negative("force", f)?;
        if f == 0.0 {
            return Ok(self.state_with(self.sorted[0], 0));
        }
        let target = f / (self.modulus * self.dx);
        // At d = g_j (0-based, sorted) the force is j g_j - S_j, non-decreasing in j.
        // With J the last j where that is <= target, springs 0..=J touch: m = J + 1.
        let (mut lo, mut hi) = (0usize, self.sorted.len());
        while hi - lo > 1 {
            let mid = (lo + hi) / 2;
            if mid as f64 * self.sorted[mid] - self.prefix[mid] <= target {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let m = lo + 1;
        let d = (target + self.prefix[m]) / m as f64;
        Ok(self.state_with(d, m))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_line_refuses_to_extrapolate_a_table() {
        use crate::profile::{Shape, TabulatedProfile};
        let table = TabulatedProfile::new(vec![0.0, 0.5, 1.0], vec![0.0, 0.1, 0.4]).unwrap();
        let p = Profile::single(Shape::Table(table));
        assert!(half_line(&p, 10, 0.9).is_ok());
        assert!(matches!(
            half_line(&p, 10, 1.5),
            Err(MrdError::OutOfRange { .. })
        ));
    }

    #[test]
    fn force_control_inverts_depth_control_exactly() {
        let gaps: Vec<f64> = (0..1000)
            .map(|i| ((i * 7919) % 1000) as f64 * 1e-3)
            .collect();
        let f = Foundation::new(&gaps, 0.01, 2.0).unwrap();
        for &d in &[0.0005, 0.0123, 0.3004, 0.9991, 1.5] {
            let s = f.at_depth(d).unwrap();
            let t = f.at_force(s.force).unwrap();
            assert!((t.depth - d).abs() < 1e-12, "d={d} got {}", t.depth);
            assert_eq!(t.contacts, s.contacts);
            // Brute force sum.
            let brute: f64 = gaps.iter().map(|&g| (d - g).max(0.0)).sum::<f64>() * 0.02;
            assert!((s.force - brute).abs() < 1e-12 * brute.max(1.0));
        }
    }

    #[test]
    fn rejects_bad_input() {
        assert!(Foundation::new(&[0.0, f64::NAN], 1.0, 1.0).is_err());
        assert!(Foundation::new(&[], 1.0, 1.0).is_err());
        assert!(Foundation::new(&[0.0], -1.0, 1.0).is_err());
        let f = Foundation::new(&[0.0, 1.0], 1.0, 1.0).unwrap();
        assert!(f.at_force(-1.0).is_err());
    }
}
