//! Surface compliance operators u = K p of an elastic half-space (modulus E*).
//!
//! Physics apart from the solver: the periodic and the non-periodic half-space are two
//! types behind one trait, and a dense matrix (for tests on tiny grids) is a third.
//! Arrays are row-major `ny x nx` (index `j * nx + i`), cell sizes `hx = lx/nx`,
//! `hy = ly/ny`; pressures are cell averages, displacements are taken at cell centres.

//!
//! One file per job: `space` (the grid, checks, memory figures), `traits` (what the
//! solvers ask of an operator), `stiffness` (the preconditioner), `periodic`,
//! `non_periodic` and `dense` (the three operators), `table` (real-space sums),
//! `forms` (coarse and window forms, the solver's operator bound).

mod dense;
mod forms;
mod non_periodic;
mod periodic;
mod space;
mod stiffness;
mod table;
mod traits;

pub use crate::love::love_coefficient;
pub use dense::DenseCompliance;
pub use forms::{GridForms, GridOperator};
pub use non_periodic::NonPeriodicHalfSpace;
pub use periodic::{spectral_grid, PeriodicHalfSpace, COMPUTED_SYMBOLS_ABOVE};
pub use space::{
    check_scales, HalfSpace, Operand, Spectral, Transform, BYTES_PER_CELL_NON_PERIODIC,
    BYTES_PER_CELL_PERIODIC, PROCESS_BYTES, SCALE_RANGE,
};
pub use stiffness::Precision;
pub use traits::{Compliance, Preconditioner, RealSpace};

#[cfg(test)]
mod tests {
    use super::dense::*;
    use super::forms::*;
    use super::non_periodic::*;
    use super::periodic::*;
    use super::space::*;
    use super::stiffness::*;
    use super::table::*;
    use super::traits::*;
    use crate::fft::*;
    use crate::symbol::*;
    use rayon::prelude::*;

    /// The periodic half-space's symbols, computed as the transforms read them (grids
    /// above [`COMPUTED_SYMBOLS_ABOVE`]) or stored, are those of `spectral` bit for bit (K
    /// in double and single precision, M in single): the same operations on the same
    /// values, so every product and result is the same.
    #[test]
    fn computed_symbols_are_the_stored_ones_bit_for_bit() {
        use crate::symbol::full_symbol;
        let grids = [
            (8, 8, 1.0, 1.0),
            (7, 5, 1.0, 0.8),
            (12, 9, 2.0, 0.7),
            (6, 10, 0.3, 1.0),
        ];
        for (nx, ny, lx, ly) in grids {
            let e_star = 2.5;
            let nc = nx / 2 + 1;
            let stiffness = spectral(nx, ny, lx, ly, stiffness_law(lx, ly, e_star));
            let kernel = spectral(nx, ny, lx, ly, compliance_law(e_star));
            let bits64 = |v: Vec<f64>| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            let bits32 = |v: Vec<f32>| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            let to32 = |v: &[f64]| v.iter().map(|&x| x as f32).collect::<Vec<_>>();
            for computed in [true, false] {
                let op = PeriodicHalfSpace::with_symbols(nx, ny, (lx, ly), e_star, computed);
                assert_eq!(matches!(op.kernel, Symbol::Radial(_)), computed);
                let got = full_symbol(&op.kernel, nc, ny);
                assert_eq!(bits64(got), bits64(kernel.clone()), "{nx}x{ny}");
                let Stiffness::Single(_, m, Some(k32)) = &op.stiffness else {
                    panic!("single-precision M with K")
                };
                assert_eq!(bits32(full_symbol(m, nc, ny)), bits32(to32(&stiffness)));
                assert_eq!(bits32(full_symbol(k32, nc, ny)), bits32(to32(&kernel)));
            }
        }
    }

    /// `fft` and `reference` applied to the same pressures agree within 1e-12 of the
    /// largest displacement.
    fn check(fft: &mut dyn Compliance, reference: &mut dyn Compliance) {
        let n = fft.cells();
        let p: Vec<f64> = (0..n)
            .map(|k| ((k * 2654435761) % 1000) as f64 / 1000.0)
            .collect();
        let (mut u1, mut u2) = (vec![0.0; n], vec![0.0; n]);
        fft.apply(&p, &mut u1);
        reference.apply(&p, &mut u2);
        let scale = u2.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (a, b) in u1.iter().zip(&u2) {
            assert!((a - b).abs() <= 1e-12 * scale, "{a} vs {b}");
        }
    }

    /// K (double and single) and M of one operator share one row buffer: applied in
    /// any order, each gives what a fresh operator gives, bit for bit; rows loaded for
    /// one and abandoned when another takes the buffer cannot be finished (a panic,
    /// never the other's values).
    #[test]
    fn shared_row_buffer_changes_no_bit_and_refuses_abandoned_rows() {
        use crate::fft::copy_in;
        // K by its single-precision transform (what the solver's early iterations use).
        fn k_single(op: &mut dyn GridOperator, p: &[f64]) -> Vec<f64> {
            let mut u = vec![0.0; p.len()];
            let s = op.spectral(Operand::ComplianceSingle).unwrap();
            match s.transform {
                Transform::Single(f, k) => f.convolve(p, s.dims, k, &mut u),
                Transform::Double(..) => panic!("no single-precision K"),
            }
            u
        }
        type Make = fn(usize, usize) -> Box<dyn GridOperator>;
        // Each from an operator of its own.
        fn each(make: Make, nx: usize, ny: usize, p: &[f64]) -> [Vec<f64>; 3] {
            let (mut k, mut m) = (vec![0.0; p.len()], p.to_vec());
            make(nx, ny).apply(p, &mut k);
            let ks = k_single(&mut *make(nx, ny), p);
            make(nx, ny).precondition(&mut m);
            [k, ks, m]
        }
        for (nx, ny) in [(16usize, 12usize), (9, 14)] {
            let p: Vec<f64> = (0..nx * ny).map(|k| ((k * 37) % 11) as f64 - 5.0).collect();
            let ops: [Make; 2] = [
                |nx, ny| Box::new(PeriodicHalfSpace::new(nx, ny, 1.0, 0.8, 2.0)),
                |nx, ny| Box::new(NonPeriodicHalfSpace::new(nx, ny, 1.0, 0.8, 2.0)),
            ];
            for make in ops {
                let want = each(make, nx, ny, &p);
                assert_ne!(want[0], want[1], "K in single precision differs from K");
                let mut shared = make(nx, ny);
                for _ in 0..2 {
                    // M first, then K in single and double precision, and back.
                    let mut m = p.clone();
                    shared.precondition(&mut m);
                    let ks = k_single(&mut *shared, &p);
                    let mut k = vec![0.0; nx * ny];
                    shared.apply(&p, &mut k);
                    assert_eq!([k, ks, m], want, "{nx}x{ny}");
                }
                // Rows loaded for M, the buffer then taken by K: finishing them panics.
                let chunk = nx * crate::fft::ROWS_PER_CHUNK;
                let dims = (nx, ny);
                match shared.spectral(Operand::Preconditioner).unwrap().transform {
                    Transform::Single(f, _) => f.load_rows(dims, p.par_chunks(chunk), copy_in),
                    Transform::Double(f, _) => f.load_rows(dims, p.par_chunks(chunk), copy_in),
                };
                let mut k = vec![0.0; nx * ny];
                shared.apply(&p, &mut k);
                let finish =
                    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                        match shared.spectral(Operand::Preconditioner).unwrap().transform {
                            Transform::Single(f, s) => f.convolve_columns(s),
                            Transform::Double(f, s) => f.convolve_columns(s),
                        }
                    }));
                assert!(finish.is_err(), "abandoned rows finished");
            }
        }
    }

    #[test]
    fn fft_operators_match_dense_matrices_to_1e12() {
        for &(nx, ny) in &[(8usize, 8usize), (7, 5), (12, 9)] {
            let mut np = NonPeriodicHalfSpace::new(nx, ny, 1.0, 0.8, 2.0);
            check(&mut np, &mut DenseCompliance::love(nx, ny, 1.0, 0.8, 2.0));
            // Square cells on a square grid: the mirrored table.
            let mut sq = NonPeriodicHalfSpace::new(nx, nx, 1.0, 1.0, 2.0);
            check(&mut sq, &mut DenseCompliance::love(nx, nx, 1.0, 1.0, 2.0));
            let mut pe = PeriodicHalfSpace::new(nx, ny, 1.0, 0.8, 2.0);
            check(
                &mut pe,
                &mut DenseCompliance::periodic(nx, ny, 1.0, 0.8, 2.0),
            );
        }
    }

    #[test]
    fn point_loads_match_the_operator_to_1e12() {
        // Loads near every edge and corner exercise the wrap-around of the tables.
        for &(nx, ny) in &[(8usize, 8usize), (7, 5), (12, 9)] {
            let n = nx * ny;
            let loads = vec![(0, 1.5), (n - 1, -0.7), (nx - 1, 2.0), (n / 2 + 1, 0.3)];
            let ly = 0.8 * ny as f64 / nx as f64;
            let ops: Vec<Box<dyn RealSpace>> = vec![
                Box::new(PeriodicHalfSpace::new(nx, ny, 1.0, 0.8, 2.0)),
                Box::new(NonPeriodicHalfSpace::new(nx, ny, 1.0, 0.8, 2.0)),
                // Square cells (square grids: the table built from a triangle).
                Box::new(NonPeriodicHalfSpace::new(nx, ny, 0.8, ly, 2.0)),
                Box::new(DenseCompliance::love(nx, ny, 1.0, 0.8, 2.0)),
            ];
            for mut op in ops {
                let mut q = vec![0.0; n];
                for &(c, v) in &loads {
                    q[c] += v;
                }
                let base: Vec<f64> = (0..n).map(|k| k as f64 * 0.01).collect();
                let mut want = vec![0.0; n];
                op.apply(&q, &mut want);
                want.iter_mut().zip(&base).for_each(|(a, b)| *a += b);
                let mut got = base.clone();
                op.add_point_loads(&loads, &mut got);
                let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                for (a, b) in got.iter().zip(&want) {
                    assert!((a - b).abs() <= 1e-12 * scale, "{nx}x{ny}: {a} vs {b}");
                }
                // The same sums at a few cells only (operators with a table).
                let at = [n - 1, 0, nx, n / 2, 1];
                if let Some(u) = op.displacements_at(&at, &loads) {
                    for (&c, u) in at.iter().zip(&u) {
                        let b = want[c] - base[c];
                        assert!(
                            (u - b).abs() <= 1e-12 * scale,
                            "{nx}x{ny} at {c}: {u} vs {b}"
                        );
                    }
                }
            }
        }
        // Both FFT operators have a table.
        let (at, loads) = ([3usize], [(5usize, 1.0)]);
        assert!(PeriodicHalfSpace::new(4, 4, 1.0, 1.0, 1.0)
            .displacements_at(&at, &loads)
            .is_some());
        assert!(NonPeriodicHalfSpace::new(4, 4, 1.0, 1.0, 1.0)
            .displacements_at(&at, &loads)
            .is_some());
    }

    #[test]
    fn a_table_even_in_y_keeps_a_quarter_and_reads_the_full_one_to_rounding() {
        // Every periodic half-space's symbol is even in ky (and, being real, in kx): its
        // table keeps offsets r <= ny/2, d <= nx/2 and reads the mirrors (odd and even
        // sizes). Against the full inverse transform of the symbol: the same responses
        // to rounding (1e-15 of the largest), the stored quarter bit for bit; a single
        // load at every cell against K's transform (the mirrored stretches of each row).
        for &(nx, ny) in &[(8usize, 8usize), (7, 5), (12, 9), (6, 10), (5, 3), (2, 4)] {
            let mut op = PeriodicHalfSpace::new(nx, ny, 1.0, 0.8, 2.0);
            assert!(op.table.even);
            assert_eq!(
                op.table.values.len(),
                (ny / 2 + 1).min(ny) * (nx / 2 + 1).min(nx)
            );
            let full_kernel = crate::symbol::full_symbol(&op.kernel, nx / 2 + 1, ny);
            let mut full = vec![0.0; nx * ny];
            Fft2::<f64>::new(nx, ny).inverse_of_real(&full_kernel, &mut full);
            let scale = full.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for j in 0..ny {
                for i in 0..nx {
                    let (got, want) = (op.table.value((i, j), (0, 0)), full[j * nx + i]);
                    if j <= ny / 2 && i <= nx / 2 {
                        assert_eq!(got.to_bits(), want.to_bits(), "{nx}x{ny} ({i}, {j})");
                    } else {
                        assert!((got - want).abs() <= 1e-15 * scale, "{nx}x{ny} ({i}, {j})");
                    }
                }
            }
            let n = nx * ny;
            for c in 0..n {
                let mut unit = vec![0.0; n];
                unit[c] = -1.5;
                let mut want = vec![0.0; n];
                op.apply(&unit, &mut want);
                let mut got = vec![0.0; n];
                op.add_point_loads(&[(c, -1.5)], &mut got);
                for (k, (a, b)) in got.iter().zip(&want).enumerate() {
                    assert!((a - b).abs() <= 1e-14 * scale, "{nx}x{ny} load {c} at {k}");
                    let v = op.table.value((k % nx, k / nx), (c % nx, c / nx));
                    assert!(-1.5 * v == *a, "{nx}x{ny} {c} {k}");
                }
            }
        }
        // A compliance odd in ky (kx ky terms) keeps its whole table.
        let odd = PeriodicHalfSpace::with_compliance(8, 6, 1.0, 1.0, 1.0, |kx, ky| {
            1.0 / (kx * kx + ky * ky).sqrt() * (1.0 + 0.3 * (kx * ky).tanh())
        });
        assert!(!odd.table.even);
        assert_eq!(odd.table.values.len(), 8 * 6);
    }

    #[test]
    fn restricted_matrices_and_their_single_copies() {
        // K between listed cells, built in a reused buffer (larger, smaller, empty): the
        // same matrix bit for bit as in fresh storage, entry (a, b) K's response at
        // cells[a] to a load at cells[b].
        let mut op = PeriodicHalfSpace::new(48, 32, 1.0, 0.8, 2.0);
        let n = op.cells();
        let sets: [Vec<usize>; 3] = [
            (0..n).filter(|k| k % 4 != 0).collect(),
            (3..n).step_by(2).collect(),
            vec![7, 100, 191],
        ];
        let fresh: Vec<Vec<f64>> = sets
            .iter()
            .map(|c| op.restricted(c, Vec::new()).unwrap())
            .collect();
        let mut buffer = Vec::new();
        for (cells, want) in sets.iter().zip(&fresh) {
            buffer = op.restricted(cells, buffer).unwrap();
            assert_eq!(&buffer, want);
        }
        let cells = &sets[0];
        let m = cells.len();
        let mut unit = vec![0.0; n];
        unit[cells[4]] = 1.0;
        let mut u = vec![0.0; n];
        op.apply(&unit, &mut u);
        for (a, &c) in cells.iter().enumerate() {
            let v = fresh[0][a * m + 4];
            assert!((v - u[c]).abs() <= 1e-12 * u[cells[4]], "{v} vs {}", u[c]);
        }
        // The copy in single precision (1152 cells; storage reused from a larger
        // matrix): K t within 1e-7 of the double-precision product, and exactly the
        // product of the rounded entries (sums in double precision); K p and point
        // loads untouched. None below SINGLE_COPY_MIN cells (767 here) and for tests'
        // matrices.
        let hs = (1.0 / 48.0, 0.8 / 32.0);
        let mut dense =
            DenseCompliance::from_matrix(m, hs, 2.0, fresh[0].clone(), vec![1.0; 2 * m * m]);
        assert!(m >= SINGLE_COPY_MIN && dense.rounds_single());
        let small = sets[1].len();
        assert!(small < SINGLE_COPY_MIN);
        let mut below = DenseCompliance::from_matrix(small, hs, 2.0, fresh[1].clone(), Vec::new());
        assert!(!below.rounds_single());
        assert!(!DenseCompliance::love(3, 3, 1.0, 1.0, 1.0).rounds_single());
        let p: Vec<f64> = (0..m).map(|k| ((k * 37) % 11) as f64 - 4.0).collect();
        let (mut double, mut single) = (vec![0.0; m], vec![0.0; m]);
        dense.apply(&p, &mut double);
        dense.apply_single(&p, &mut single);
        let scale = double.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        let rounded: Vec<f64> = fresh[0].iter().map(|&v| v as f32 as f64).collect();
        for a in 0..m {
            let want: f64 = (0..m).map(|b| rounded[a * m + b] * p[b]).sum();
            assert!((single[a] - want).abs() <= 1e-13 * scale);
            assert!((single[a] - double[a]).abs() <= 1e-7 * scale);
            let exact: f64 = (0..m).map(|b| fresh[0][a * m + b] * p[b]).sum();
            assert!((double[a] - exact).abs() <= 1e-13 * scale);
        }
        assert!(single != double, "the copy is rounded");
        // Point loads: the column-wise sums in list order, bit for bit.
        let loads = [(3usize, 0.5), (0, -1.25), (m - 1, 2.0), (3, 0.75)];
        let mut want: Vec<f64> = (0..m).map(|k| k as f64 * 0.01).collect();
        let mut got = want.clone();
        for &(c, v) in &loads {
            for (a, w) in want.iter_mut().enumerate() {
                *w += fresh[0][a * m + c] * v;
            }
        }
        dense.add_point_loads(&loads, &mut got);
        assert_eq!(got, want);
    }

    #[test]
    fn a_window_is_the_half_space_of_its_cells() {
        // The window's operator (coefficients copied from the grid's table) against an
        // operator built for the window's cells: the same convolution and direct sums
        // to rounding (a wrong offset in the copy shows at 1e-2), on square and
        // rectangular cells, square and oblong windows.
        for &(nx, ny, lx, ly, wx, wy) in &[
            (12usize, 12usize, 1.0, 1.0, 5usize, 7usize),
            (12, 9, 1.0, 0.8, 9, 4),
            (8, 8, 1.0, 1.0, 8, 8),
        ] {
            let grid = NonPeriodicHalfSpace::new(nx, ny, lx, ly, 2.0);
            let (hx, hy) = (lx / nx as f64, ly / ny as f64);
            let mut win = grid.window(wx, wy).expect("a window inside the grid");
            let mut fresh = NonPeriodicHalfSpace::new(wx, wy, wx as f64 * hx, wy as f64 * hy, 2.0);
            check(&mut win, &mut fresh);
            let n = wx * wy;
            let loads = [(0, 1.0), (n - 1, 0.5), (wx + 1, -0.25)];
            let at: Vec<usize> = (0..n).collect();
            let (u, v) = (
                win.displacements_at(&at, &loads).unwrap(),
                fresh.displacements_at(&at, &loads).unwrap(),
            );
            let scale = v.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for (x, y) in u.iter().zip(&v) {
                assert!((x - y).abs() <= 1e-12 * scale, "{wx}x{wy} sums: {x} vs {y}");
            }
        }
        assert!(NonPeriodicHalfSpace::new(4, 4, 1.0, 1.0, 1.0)
            .window(5, 1)
            .is_none());
    }
}
