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
    /// Per-row copy of the real input (realfft overwrites its input); grown to the
    /// rows actually transformed.
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
            real_tmp: Vec::new(),
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
        self.forward_padded(input, self.nx, self.ny, spec);
    }

    /// Forward transform of a zero-padded input: the first `rows` rows of the grid
    /// hold `input`'s rows (`width <= nx` values each, the rest of the row zero), the
    /// other rows are zero. Zero rows are not transformed.
    pub fn forward_padded(
        &mut self,
        input: &[f64],
        width: usize,
        rows: usize,
        spec: &mut [Complex64],
    ) {
        let (nx, nc) = (self.nx, self.nc);
        let rows = rows.min(self.ny);
        if self.real_tmp.len() < rows * nx {
            self.real_tmp.resize(rows * nx, 0.0);
        }
        let r2c = &self.r2c;
        self.real_tmp[..rows * nx]
            .par_chunks_mut(nx * ROW_CHUNK)
            .zip(self.rows[..rows * nc].par_chunks_mut(nc * ROW_CHUNK))
            .zip(input[..rows * width].par_chunks(width * ROW_CHUNK))
            .for_each(|((rin, rout), src)| {
                let mut scratch = r2c.make_scratch_vec();
                for ((a, b), s) in rin
                    .chunks_mut(nx)
                    .zip(rout.chunks_mut(nc))
                    .zip(src.chunks(width))
                {
                    a[..width].copy_from_slice(s);
                    a[width..].iter_mut().for_each(|v| *v = 0.0);
                    r2c.process_with_scratch(a, b, &mut scratch)
                        .expect("row fft");
                }
            });
        transpose_padded(&self.rows, spec, self.ny, nc, rows);
        batch_fft(&self.fwd_y, spec, self.ny);
    }

    /// Inverse transform of `spec` (`nc x ny`, destroyed) into `output` (`ny x nx`),
    /// normalised so that inverse(forward(x)) = x.
    pub fn inverse(&mut self, spec: &mut [Complex64], output: &mut [f64]) {
        self.inverse_cropped(spec, output, self.nx, self.ny);
    }

    /// As [`Self::inverse`] keeping only the first `rows` rows and `width <= nx`
    /// columns (`output` is `rows x width`); discarded rows are not computed.
    pub fn inverse_cropped(
        &mut self,
        spec: &mut [Complex64],
        output: &mut [f64],
        width: usize,
        rows: usize,
    ) {
        let (nx, nc, ny) = (self.nx, self.nc, self.ny);
        let rows = rows.min(ny);
        batch_fft(&self.inv_y, spec, ny);
        transpose_rows(spec, &mut self.rows, nc, ny, rows);
        let c2r = &self.c2r;
        let norm = 1.0 / (nx * ny) as f64;
        self.rows[..rows * nc]
            .par_chunks_mut(nc * ROW_CHUNK)
            .zip(output[..rows * width].par_chunks_mut(width * ROW_CHUNK))
            .for_each(|(rin, rout)| {
                let mut scratch = c2r.make_scratch_vec();
                let mut full = if width < nx {
                    vec![0.0; nx]
                } else {
                    Vec::new()
                };
                for (a, b) in rin.chunks_mut(nc).zip(rout.chunks_mut(width)) {
                    // The DC and Nyquist imaginary parts must vanish for c2r; they do up
                    // to rounding for real data, so clear them.
                    a[0].im = 0.0;
                    if nx.is_multiple_of(2) {
                        a[nc - 1].im = 0.0;
                    }
                    if width < nx {
                        c2r.process_with_scratch(a, &mut full, &mut scratch)
                            .expect("row ifft");
                        for (o, v) in b.iter_mut().zip(&full) {
                            *o = v * norm;
                        }
                    } else {
                        c2r.process_with_scratch(a, b, &mut scratch)
                            .expect("row ifft");
                        b.iter_mut().for_each(|v| *v *= norm);
                    }
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

/// Transposes `src` (`rows x cols`, of which only the first `filled` rows are read; the
/// others count as zero) into `dst` (`cols x rows`), in blocks.
fn transpose_padded(
    src: &[Complex64],
    dst: &mut [Complex64],
    rows: usize,
    cols: usize,
    filled: usize,
) {
    const B: usize = 32;
    dst.par_chunks_mut(rows * B)
        .enumerate()
        .for_each(|(cb, dchunk)| {
            let c0 = cb * B;
            let c1 = (c0 + B).min(cols);
            for r0 in (0..filled).step_by(B) {
                let r1 = (r0 + B).min(filled);
                for c in c0..c1 {
                    let drow = &mut dchunk[(c - c0) * rows..(c - c0 + 1) * rows];
                    for r in r0..r1 {
                        drow[r] = src[r * cols + c];
                    }
                }
            }
            for c in c0..c1 {
                dchunk[(c - c0) * rows + filled..(c - c0 + 1) * rows]
                    .iter_mut()
                    .for_each(|v| *v = Complex64::default());
            }
        });
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

    #[test]
    fn padded_and_cropped_transforms_match_full_ones() {
        let (nx, ny, w, rows) = (12usize, 10usize, 5usize, 4usize);
        let small: Vec<f64> = (0..w * rows).map(|k| (k * 31 % 17) as f64 - 8.0).collect();
        let mut full = vec![0.0; nx * ny];
        for j in 0..rows {
            full[j * nx..j * nx + w].copy_from_slice(&small[j * w..(j + 1) * w]);
        }
        let mut f = Fft2::new(nx, ny);
        let (mut s1, mut s2) = (
            vec![Complex64::default(); f.spectrum_len()],
            vec![Complex64::default(); f.spectrum_len()],
        );
        f.forward(&full, &mut s1);
        // Stale values in the buffers must not leak into a padded transform.
        f.forward_padded(&small, w, rows, &mut s2);
        assert_eq!(s1, s2);
        let mut back = vec![0.0; w * rows];
        f.inverse_cropped(&mut s2, &mut back, w, rows);
        for (a, b) in small.iter().zip(&back) {
            assert!((a - b).abs() < 1e-13, "{a} vs {b}");
        }
    }
}
