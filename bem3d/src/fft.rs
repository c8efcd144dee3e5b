//! Real 2D FFT on row-major `ny x nx` arrays, spectrum kept transposed.
//!
//! Forward: real-to-complex FFT of each row (length nx, `nx/2 + 1` outputs), a blocked
//! transpose to `(nx/2 + 1) x ny`, then contiguous complex FFTs of length ny. Inverse
//! reverses the steps. Plans and scratch are created once; rows, transposes and column
//! batches are split over rayon threads. Each output value is computed by the same
//! sequence of operations whatever the thread count, so results are bit-identical.

use rayon::prelude::*;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::num_complex::Complex64;
use rustfft::{Fft, FftPlanner};
use std::sync::Arc;

pub struct Fft2 {
    nx: usize,
    ny: usize,
    nc: usize,
    r2c: Arc<dyn RealToComplex<f64>>,
    c2r: Arc<dyn ComplexToReal<f64>>,
    fwd_y: Arc<dyn Fft<f64>>,
    inv_y: Arc<dyn Fft<f64>>,
    /// Row spectra, `ny x nc`.
    rows: Vec<Complex64>,
    /// Per-row copy of the real input (realfft overwrites its input).
    real_tmp: Vec<f64>,
}

const ROW_CHUNK: usize = 16;

impl Fft2 {
    pub fn new(nx: usize, ny: usize) -> Self {
        let mut rp = RealFftPlanner::<f64>::new();
        let mut cp = FftPlanner::<f64>::new();
        let nc = nx / 2 + 1;
        Self {
            nx,
            ny,
            nc,
            r2c: rp.plan_fft_forward(nx),
            c2r: rp.plan_fft_inverse(nx),
            fwd_y: cp.plan_fft_forward(ny),
            inv_y: cp.plan_fft_inverse(ny),
            rows: vec![Complex64::default(); ny * nc],
            real_tmp: vec![0.0; nx * ny],
        }
    }

    /// Length of the transposed spectrum, `(nx/2 + 1) * ny`.
    pub fn spectrum_len(&self) -> usize {
        self.nc * self.ny
    }
    pub fn nc(&self) -> usize {
        self.nc
    }

    /// Forward transform of `input` (`ny x nx`, row-major) into `spec` (`nc x ny`).
    pub fn forward(&mut self, input: &[f64], spec: &mut [Complex64]) {
        self.forward_rows(input, spec, self.ny);
    }

    /// As [`Self::forward`] when only the first `rows` rows of `input` can be non-zero
    /// (zero padding): the other rows' transforms are skipped.
    pub fn forward_rows(&mut self, input: &[f64], spec: &mut [Complex64], rows: usize) {
        let (nx, nc) = (self.nx, self.nc);
        let rows = rows.min(self.ny);
        self.real_tmp[..rows * nx].copy_from_slice(&input[..rows * nx]);
        self.rows[rows * nc..]
            .iter_mut()
            .for_each(|c| *c = Complex64::default());
        let r2c = &self.r2c;
        self.real_tmp[..rows * nx]
            .par_chunks_mut(nx * ROW_CHUNK)
            .zip(self.rows[..rows * nc].par_chunks_mut(nc * ROW_CHUNK))
            .for_each(|(rin, rout)| {
                let mut scratch = r2c.make_scratch_vec();
                for (a, b) in rin.chunks_mut(nx).zip(rout.chunks_mut(nc)) {
                    r2c.process_with_scratch(a, b, &mut scratch)
                        .expect("row fft");
                }
            });
        transpose(&self.rows, spec, self.ny, nc);
        batch_fft(&self.fwd_y, spec, self.ny);
    }

    /// Inverse transform of `spec` (`nc x ny`, destroyed) into `output` (`ny x nx`),
    /// normalised so that inverse(forward(x)) = x.
    pub fn inverse(&mut self, spec: &mut [Complex64], output: &mut [f64]) {
        self.inverse_rows(spec, output, self.ny);
    }

    /// As [`Self::inverse`] computing only the first `rows` rows of `output` (the others
    /// are left untouched).
    pub fn inverse_rows(&mut self, spec: &mut [Complex64], output: &mut [f64], rows: usize) {
        let (nx, nc, ny) = (self.nx, self.nc, self.ny);
        let rows = rows.min(ny);
        batch_fft(&self.inv_y, spec, ny);
        transpose_rows(spec, &mut self.rows, nc, ny, rows);
        let c2r = &self.c2r;
        let norm = 1.0 / (nx * ny) as f64;
        self.rows[..rows * nc]
            .par_chunks_mut(nc * ROW_CHUNK)
            .zip(output[..rows * nx].par_chunks_mut(nx * ROW_CHUNK))
            .for_each(|(rin, rout)| {
                let mut scratch = c2r.make_scratch_vec();
                for (a, b) in rin.chunks_mut(nc).zip(rout.chunks_mut(nx)) {
                    // The DC and Nyquist imaginary parts must vanish for c2r; they do up
                    // to rounding for real data, so clear them.
                    a[0].im = 0.0;
                    if nx.is_multiple_of(2) {
                        a[nc - 1].im = 0.0;
                    }
                    c2r.process_with_scratch(a, b, &mut scratch)
                        .expect("row ifft");
                    b.iter_mut().for_each(|v| *v *= norm);
                }
            });
    }
}

fn batch_fft(fft: &Arc<dyn Fft<f64>>, data: &mut [Complex64], len: usize) {
    let per = (data.len() / len)
        .div_ceil(rayon::current_num_threads().max(1) * 4)
        .max(1);
    data.par_chunks_mut(len * per).for_each(|chunk| {
        let mut scratch = vec![Complex64::default(); fft.get_inplace_scratch_len()];
        fft.process_with_scratch(chunk, &mut scratch);
    });
}

/// Transposes the first `keep` columns of `src` (`rows x cols`) into the first `keep`
/// rows of `dst` (`cols x rows`).
fn transpose_rows(src: &[Complex64], dst: &mut [Complex64], rows: usize, cols: usize, keep: usize) {
    const B: usize = 32;
    dst[..keep * rows]
        .par_chunks_mut(rows * B)
        .enumerate()
        .for_each(|(cb, dchunk)| {
            let c0 = cb * B;
            let c1 = (c0 + B).min(keep);
            for r0 in (0..rows).step_by(B) {
                let r1 = (r0 + B).min(rows);
                for c in c0..c1 {
                    let drow = &mut dchunk[(c - c0) * rows..(c - c0 + 1) * rows];
                    for r in r0..r1 {
                        drow[r] = src[r * cols + c];
                    }
                }
            }
        });
}

/// Transposes `src` (`rows x cols`) into `dst` (`cols x rows`), in blocks.
fn transpose(src: &[Complex64], dst: &mut [Complex64], rows: usize, cols: usize) {
    transpose_rows(src, dst, rows, cols, cols);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn naive_dft(x: &[f64], nx: usize, ny: usize, kx: usize, ky: usize) -> Complex64 {
        let mut s = Complex64::default();
        for j in 0..ny {
            for i in 0..nx {
                let ph = -2.0
                    * std::f64::consts::PI
                    * ((kx * i) as f64 / nx as f64 + (ky * j) as f64 / ny as f64);
                s += Complex64::from_polar(x[j * nx + i], ph);
            }
        }
        s
    }

    #[test]
    fn matches_naive_dft_and_round_trips() {
        for &(nx, ny) in &[(8usize, 6usize), (7, 5), (16, 16), (9, 12)] {
            let x: Vec<f64> = (0..nx * ny)
                .map(|k| ((k * 7919) % 97) as f64 / 97.0 - 0.3)
                .collect();
            let mut f = Fft2::new(nx, ny);
            let mut spec = vec![Complex64::default(); f.spectrum_len()];
            f.forward(&x, &mut spec);
            for kx in 0..f.nc() {
                for ky in 0..ny {
                    let d = naive_dft(&x, nx, ny, kx, ky);
                    assert!(
                        (spec[kx * ny + ky] - d).norm() < 1e-12,
                        "{nx}x{ny} ({kx},{ky})"
                    );
                }
            }
            let mut back = vec![0.0; nx * ny];
            f.inverse(&mut spec, &mut back);
            for (a, b) in x.iter().zip(&back) {
                assert!((a - b).abs() < 1e-14);
            }
        }
    }
}
