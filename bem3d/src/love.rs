//! Love's influence coefficients of the non-periodic half-space: the displacement at
//! an offset from a rectangular cell under unit uniform pressure, in closed form (Love
//! 1929) and, far from the cell, by the cell's multipole expansion ([`FarField`]),
//! which costs a tenth as much and is as exact there.

/// Love (1929): surface displacement at offset (x, y) from the centre of a rectangle of
/// half-widths (a, b) under unit uniform pressure, times pi E*: the sum over the four
/// sides of `s [asinh(p/|s|) - asinh(q/|s|)]`. Each difference is taken as one asinh
/// (asinh u - asinh v = asinh(u sqrt(1 + v^2) - v sqrt(1 + u^2)), its argument written
/// without cancellation), so far-field values keep their precision: within 1.2e-12 of
/// 50-digit values out to 4095 cells (two asinh per side: 1.8e-10), at half the cost.
/// The sides are summed in an order that makes the value exactly symmetric in (x, a)
/// and (y, b).
pub fn love_coefficient(x: f64, y: f64, a: f64, b: f64) -> f64 {
    let (k, l, m, n) = (x + a, x - a, y + b, y - b);
    // Distances from the four corners.
    let r = |u: f64, v: f64| (u * u + v * v).sqrt();
    let (rkm, rkn, rlm, rln) = (r(k, m), r(k, n), r(l, m), r(l, n));
    // One side: s [asinh(p/|s|) - asinh(q/|s|)] with rp = |(s, p)|, rq = |(s, q)|;
    // s = 0 contributes 0.
    let side = |s: f64, p: f64, q: f64, rp: f64, rq: f64| -> f64 {
        if s == 0.0 {
            return 0.0;
        }
        let arg = if p * q > 0.0 {
            // (p rq - q rp) / s^2 with the cancellation of like signs removed.
            (p - q) * (p + q) / (p * rq + q * rp)
        } else {
            (p * rq - q * rp) / (s * s)
        };
        s * arg.asinh()
    };
    (side(k, m, n, rkm, rkn) + side(m, k, l, rkm, rlm))
        + (side(l, n, m, rln, rlm) + side(n, l, k, rln, rkn))
}

/// Highest order of the far-field expansion (even).
const ORDER: usize = 10;
/// Orders 0, 2, .., ORDER.
const TERMS: usize = ORDER / 2 + 1;
/// The expansion serves offsets at least this many half-widths (the larger) from the
/// cell's centre.
const REACH: f64 = 20.0;

/// Love's coefficient far from the cell: 1/r expanded in a Taylor series about the
/// cell's centre and integrated over the rectangle term by term (odd orders vanish),
/// `sum over even m, k with m + k <= 10 of M_m(a) M_k(b) T_mk(x, y)`, where
/// `M_m(a) = 2 a^(m+1) / (m + 1)` is the m-th moment of the side and
/// `T_mk = (-d/dx)^m (-d/dy)^k (1/r) / (m! k!) = P_mk(x, y) / r^(2(m+k)+1)`, P_mk
/// homogeneous polynomials of degree m + k from the recurrence of 1/r's Taylor
/// coefficients, `n P_mk = (2n - 1)(x P_(m-1)k + y P_m(k-1)) - (n - 1) r^2 (P_(m-2)k +
/// P_m(k-2))`, n = m + k. The series converges beyond the cell's corners; from
/// [`REACH`] half-widths the first omitted order (12) is below rounding: a prototype
/// of this sum was within 4.2e-16 relative of 50-digit values of the closed form
/// (mpmath; 19 directions, 6 radii from 20 half-widths to 800, square and 5:4 cells;
/// orders up to 8 gave 2.8e-14, up to 6 1.2e-11), and the tests hold this code to
/// 2e-15, where the closed form itself loses up to 1.2e-12 to cancellation. Per order the sum is a polynomial in
/// `t = x^2 / r^2` times `r^-(n+1)`, its coefficients made once per cell shape.
pub(crate) struct FarField {
    /// Order 2h's polynomial in t, coefficients of t^0..t^h.
    orders: [[f64; TERMS]; TERMS],
    /// Squared distance from which the expansion serves.
    reach2: f64,
}

impl FarField {
    /// The expansion for cells of half-widths (a, b).
    pub(crate) fn new(a: f64, b: f64) -> Self {
        // p[m][k]: coefficients of x^i y^(m+k-i), i = 0..=m+k.
        let mut p = vec![vec![Vec::<f64>::new(); ORDER + 1]; ORDER + 1];
        p[0][0] = vec![1.0];
        for n in 1..=ORDER {
            for m in 0..=n {
                let k = n - m;
                let mut c = vec![0.0; n + 1];
                let (f1, f2) = ((2 * n - 1) as f64, (n - 1) as f64);
                if m >= 1 {
                    // x P_(m-1)k
                    for (i, v) in p[m - 1][k].iter().enumerate() {
                        c[i + 1] += f1 * v;
                    }
                }
                if k >= 1 {
                    // y P_m(k-1)
                    for (i, v) in p[m][k - 1].iter().enumerate() {
                        c[i] += f1 * v;
                    }
                }
                let lower = [(m >= 2).then(|| (m - 2, k)), (k >= 2).then(|| (m, k - 2))];
                for (mm, kk) in lower.into_iter().flatten() {
                    // r^2 P = (x^2 + y^2) P
                    for (i, v) in p[mm][kk].iter().enumerate() {
                        c[i + 2] -= f2 * v;
                        c[i] -= f2 * v;
                    }
                }
                p[m][k] = c.into_iter().map(|v| v / n as f64).collect();
            }
        }
        let moment = |s: f64, m: usize| 2.0 * s.powi(m as i32 + 1) / (m + 1) as f64;
        let mut orders = [[0.0; TERMS]; TERMS];
        for (h, order) in orders.iter_mut().enumerate() {
            let n = 2 * h;
            // Q_n = sum over even m of M_m(a) M_(n-m)(b) P_m(n-m): only even powers of x.
            for m in (0..=n).step_by(2) {
                let w = moment(a, m) * moment(b, n - m);
                for q in 0..=h {
                    // x^2q y^(n-2q) / r^n = t^q (1 - t)^(h-q)
                    let c = w * p[m][n - m][2 * q];
                    let mut binomial = 1.0;
                    for j in 0..=h - q {
                        let sign = if j % 2 == 0 { 1.0 } else { -1.0 };
                        order[q + j] += sign * binomial * c;
                        binomial = binomial * (h - q - j) as f64 / (j + 1) as f64;
                    }
                }
            }
        }
        let reach = REACH * a.max(b);
        Self {
            orders,
            reach2: reach * reach,
        }
    }

    /// Whether the expansion serves the offset (x, y).
    pub(crate) fn reaches(&self, x: f64, y: f64) -> bool {
        x * x + y * y >= self.reach2
    }

    /// Love's coefficient at (x, y) (see [`love_coefficient`]); for offsets it
    /// [`reaches`](Self::reaches).
    pub(crate) fn value(&self, x: f64, y: f64) -> f64 {
        let r2 = x * x + y * y;
        let (t, s) = (x * x / r2, 1.0 / r2);
        let mut sum = 0.0;
        for (h, order) in self.orders.iter().enumerate().rev() {
            let poly = order[..=h].iter().rev().fold(0.0, |acc, &c| acc * t + c);
            sum = sum * s + poly;
        }
        sum / r2.sqrt()
    }

    /// Love's coefficient at (x, y) for this expansion's cell of half-widths (a, b):
    /// the expansion where it reaches, else the closed form.
    pub(crate) fn coefficient(&self, x: f64, y: f64, a: f64, b: f64) -> f64 {
        if self.reaches(x, y) {
            self.value(x, y)
        } else {
            love_coefficient(x, y, a, b)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn love_coefficient_matches_50_digit_values() {
        // Love's formula for a cell of half-width 1/2 evaluated with mpmath at 50 digits
        // (the same four sides, each as two asinh; rounded to the nearest f64): offsets
        // from the centre cell to the far field of a 4096^2 grid. Two asinh per side in
        // f64 are 1.8e-10 off at (1000, 999).
        let want = [
            (0.0, 0.0, 3.525494348078172),
            (1.0, 0.0, 1.038049735904756),
            (1.0, 1.0, 0.72469743813433),
            (3.0, 2.0, 0.2782588155883612),
            (10.0, 7.0, 0.08194614720844572),
            (100.0, 3.0, 0.009995544645346317),
            (1000.0, 0.0, 0.001000000041666663),
            (1000.0, 999.0, 0.0007074604376747299),
            (2047.0, 2047.0, 0.0003454356544710393),
            (4095.0, 1.0, 0.0002442002375257293),
            (12.0, 511.0, 0.001956408100176102),
        ];
        for (x, y, v) in want {
            for (x, y) in [(x, y), (y, x), (-x, y)] {
                let got = love_coefficient(x, y, 0.5, 0.5);
                let err = (got / v - 1.0).abs();
                assert!(err <= 1.5e-12, "({x}, {y}): {got} vs {v}: {err:e}");
            }
        }
    }

    #[test]
    fn love_coefficient_is_exactly_symmetric_on_square_cells() {
        // The operator mirrors its table on square grids: this must hold bit for bit.
        for j in 0..40 {
            for i in 0..40 {
                let (x, y) = (i as f64 * 0.37, j as f64 * 0.37 + 0.01 * (i % 3) as f64);
                let (a, b) = (
                    love_coefficient(x, y, 0.185, 0.185),
                    love_coefficient(y, x, 0.185, 0.185),
                );
                assert_eq!(a.to_bits(), b.to_bits(), "({x}, {y})");
            }
        }
    }

    #[test]
    fn love_coefficient_centre_value() {
        // Centre of a square of side 2a: u = (4 a ln(1 + sqrt 2)) / (pi E*) * 2 ...
        // Johnson (1985) 3.25: w(0) = (2/pi) p a 2 ln(1+sqrt2) (1-nu^2)/E for side 2a.
        let a = 0.5;
        let f = love_coefficient(0.0, 0.0, a, a);
        assert!((f - 8.0 * a * (1.0 + 2f64.sqrt()).ln()).abs() < 1e-14);
        // Far field: a point force, u = F / (pi E* r), F = 4ab.
        let r = 1e3;
        let f = love_coefficient(r, 0.0, a, a);
        assert!((f / (4.0 * a * a / r) - 1.0).abs() < 1e-6);
    }

    #[test]
    fn far_field_matches_50_digit_values() {
        // The closed form at 50 digits (mpmath), rounded to the nearest f64: square
        // cells, 5:4 cells and cells of other sizes, from the expansion's reach out.
        let want = [
            (10.0, 0.0, 0.5, 0.5, 0.10004163016690379),
            (10.0, 7.0, 0.5, 0.5, 0.08194614720844572),
            (7.5, 8.5, 0.5, 0.5, 0.08824489926290274),
            (100.0, 3.0, 0.5, 0.5, 0.009995544645346317),
            (1000.0, 999.0, 0.5, 0.5, 0.0007074604376747299),
            (4095.0, 1.0, 0.5, 0.5, 0.0002442002375257293),
            (0.0, 10.5, 0.5, 0.4, 0.0761985165990229),
            (9.5, 4.0, 0.5, 0.4, 0.07764788041546639),
            (300.0, 400.0, 0.5, 0.4, 0.0016000001783468526),
            (0.25, 0.05, 0.005, 0.0125, 0.0009803516956851462),
            (2.0, 1.5, 0.05, 0.05, 0.004000266801402734),
        ];
        for (x, y, a, b, v) in want {
            let far = FarField::new(a, b);
            for (x, y) in [(x, y), (-x, y), (x, -y)] {
                assert!(far.reaches(x, y), "({x}, {y}) within the reach");
                let err = (far.value(x, y) / v - 1.0).abs();
                assert!(err <= 2e-15, "({x}, {y}, {a}, {b}): {err:e}");
            }
        }
    }

    #[test]
    fn far_field_joins_the_closed_form_at_its_reach() {
        // Just outside the reach (where the omitted order is largest) and on rings
        // beyond, in every direction: the two within the closed form's own error
        // (1.5e-12, its cancellation far out; e.g. at (328.19, 34.49) the expansion
        // is the 50-digit value to the last bit, the closed form 1e-13 off); inside
        // the reach, `coefficient` is the closed form itself.
        for (a, b) in [(0.5, 0.5), (0.5, 0.4), (0.2, 0.6)] {
            let far = FarField::new(a, b);
            let reach = REACH * f64::max(a, b);
            for deg in 0..=90 {
                let th = (deg as f64).to_radians();
                for r in [reach * 1.000001, 1.7 * reach, 33.0 * reach] {
                    let (x, y) = (r * th.cos(), r * th.sin());
                    let (f, c) = (far.value(x, y), love_coefficient(x, y, a, b));
                    assert!((f / c - 1.0).abs() <= 1.5e-12, "({x}, {y}): {f} vs {c}");
                    assert_eq!(far.coefficient(x, y, a, b), f);
                }
                let (x, y) = (0.99 * reach * th.cos(), 0.99 * reach * th.sin());
                assert!(!far.reaches(x, y));
                assert_eq!(far.coefficient(x, y, a, b), love_coefficient(x, y, a, b));
            }
        }
    }
}
