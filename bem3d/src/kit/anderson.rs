//! Anderson acceleration of a fixed-point iteration x -> G(x): the next iterate is the
//! combination of the last images whose residuals `G(x) - x` combine to the least
//! (type II; on a linear map it is GMRES-like). The outer loops of steady sliding and of
//! the exponential cohesive law use it.

/// Anderson acceleration (type II) of a fixed-point iteration x -> G(x), with the last
/// `memory` differences; sums in a fixed order (results do not depend on threads).
pub(crate) struct Anderson {
    memory: usize,
    last: Option<(Vec<f64>, Vec<f64>)>,
    d_g: Vec<Vec<f64>>,
    d_f: Vec<Vec<f64>>,
    /// `<d_f[i], d_f[j]>`, kept as the differences come and go (each pair summed once).
    gram: Vec<Vec<f64>>,
}

impl Anderson {
    pub(crate) fn new(memory: usize) -> Self {
        Self {
            memory,
            last: None,
            d_g: Vec::new(),
            d_f: Vec::new(),
            gram: Vec::new(),
        }
    }

    /// The next iterate from x and g = G(x).
    pub(crate) fn next(&mut self, x: &[f64], g: &[f64]) -> Vec<f64> {
        let f: Vec<f64> = g.iter().zip(x).map(|(g, x)| g - x).collect();
        if let Some((g0, f0)) = self.last.take() {
            self.d_g
                .push(g.iter().zip(&g0).map(|(a, b)| a - b).collect());
            let newest: Vec<f64> = f.iter().zip(&f0).map(|(a, b)| a - b).collect();
            let row: Vec<f64> = self
                .d_f
                .iter()
                .chain(std::iter::once(&newest))
                .map(|d| dot(d, &newest))
                .collect();
            for (old, v) in self.gram.iter_mut().zip(&row) {
                old.push(*v);
            }
            self.gram.push(row);
            self.d_f.push(newest);
            if self.d_f.len() > self.memory {
                self.d_g.remove(0);
                self.d_f.remove(0);
                self.gram.remove(0);
                for r in &mut self.gram {
                    r.remove(0);
                }
            }
        }
        self.last = Some((g.to_vec(), f.clone()));
        let m = self.d_f.len();
        if m == 0 {
            return g.to_vec();
        }
        // Least squares min |f - dF gamma| by the normal equations (m <= 6), regularised.
        let mut a = vec![vec![0.0; m + 1]; m];
        for i in 0..m {
            a[i][..m].copy_from_slice(&self.gram[i]);
            a[i][m] = dot(&self.d_f[i], &f);
        }
        let trace: f64 = (0..m).map(|i| a[i][i]).sum();
        for (i, row) in a.iter_mut().enumerate() {
            row[i] += 1e-10 * trace.max(f64::MIN_POSITIVE);
        }
        let gamma = match solve_small(a) {
            Some(g) => g,
            None => {
                self.d_g.clear();
                self.d_f.clear();
                self.gram.clear();
                return g.to_vec();
            }
        };
        let mut out = g.to_vec();
        for (k, gk) in gamma.iter().enumerate() {
            for (o, d) in out.iter_mut().zip(&self.d_g[k]) {
                *o -= gk * d;
            }
        }
        out
    }
}

/// `sum a b` in cell order (sums that do not depend on the threads): sequential rather
/// than `chunks::dot`, whose chunked order would round the sliding outputs otherwise;
/// a few products of the grid a round, beside a round's transforms.
fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>()
}

/// Solves the augmented m x (m + 1) system by Gaussian elimination with partial pivoting.
fn solve_small(mut a: Vec<Vec<f64>>) -> Option<Vec<f64>> {
    let m = a.len();
    for col in 0..m {
        let piv = (col..m).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[piv][col].abs() < 1e-300 {
            return None;
        }
        a.swap(col, piv);
        for row in col + 1..m {
            let f = a[row][col] / a[col][col];
            for k in col..=m {
                a[row][k] -= f * a[col][k];
            }
        }
    }
    let mut x = vec![0.0; m];
    for row in (0..m).rev() {
        let s: f64 = (row + 1..m).map(|k| a[row][k] * x[k]).sum();
        x[row] = (a[row][m] - s) / a[row][row];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On a linear contraction x -> A x + b of dimension 3 the combination of the last
    /// three differences spans the map's Krylov space: the residual falls to rounding in
    /// a few steps (GMRES-like), where the plain iteration (rate 0.9) needs hundreds.
    #[test]
    fn a_linear_map_converges_in_few_steps() {
        let a = [[0.9, 0.05, 0.0], [0.0, 0.5, 0.1], [0.02, 0.0, -0.7]];
        let b = [1.0, -2.0, 0.5];
        let map = |x: &[f64]| -> Vec<f64> {
            (0..3)
                .map(|i| (0..3).map(|j| a[i][j] * x[j]).sum::<f64>() + b[i])
                .collect()
        };
        let residual = |x: &[f64]| {
            let g = map(x);
            g.iter()
                .zip(x)
                .map(|(g, x)| (g - x).abs())
                .fold(0.0, f64::max)
        };
        let mut mixer = Anderson::new(3);
        let mut x = vec![0.0; 3];
        let mut steps = 0;
        while residual(&x) > 1e-10 && steps < 50 {
            let g = map(&x);
            x = mixer.next(&x, &g);
            steps += 1;
        }
        assert!(steps <= 8, "{steps} steps, residual {:e}", residual(&x));
        let mut plain = vec![0.0; 3];
        for _ in 0..steps {
            plain = map(&plain);
        }
        assert!(residual(&plain) > 1e-3, "the plain iteration is slow here");
    }
}
