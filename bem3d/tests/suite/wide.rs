//! The wide variants of `bem3d::wide` give the baseline variant's results bit for bit,
//! on every variant this processor has (the others are skipped and named).

use bem3d::wide::{add_scaled_reversed_with, add_scaled_with, available, dot_with, Width};

fn values(n: usize, seed: u64) -> Vec<f64> {
    // A fixed pseudo-random sequence with magnitudes over several decades, so that
    // rounding differs wherever the order of operations would.
    let mut x = seed;
    (0..n)
        .map(|_| {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let u = (x >> 11) as f64 / (1u64 << 53) as f64;
            (u - 0.5) * 10f64.powi((x % 7) as i32 - 3)
        })
        .collect()
}

#[test]
fn every_variant_gives_the_baseline_bit_for_bit() {
    let mut ran = Vec::new();
    for w in [Width::Avx2, Width::Avx512] {
        if !available(w) {
            eprintln!("{w:?}: not on this processor, skipped");
            continue;
        }
        ran.push(w);
        // Lengths around the 8-wide blocks and their tails.
        for n in [0, 1, 7, 8, 9, 15, 16, 17, 63, 64, 1000, 4099] {
            let (a, b) = (values(n, 1), values(n, 2));
            let a32: Vec<f32> = a.iter().map(|&v| v as f32).collect();
            let base = dot_with(Width::Baseline, &a, &b);
            assert_eq!(
                dot_with(w, &a, &b).to_bits(),
                base.to_bits(),
                "{w:?} dot, n = {n}"
            );
            let base32 = dot_with(Width::Baseline, &a32, &b);
            assert_eq!(
                dot_with(w, &a32, &b).to_bits(),
                base32.to_bits(),
                "{w:?} dot f32, n = {n}"
            );
            let (mut u0, mut u1) = (values(n, 3), values(n, 3));
            add_scaled_with(Width::Baseline, &mut u0, 0.37, &b);
            add_scaled_with(w, &mut u1, 0.37, &b);
            assert!(
                u0.iter().zip(&u1).all(|(x, y)| x.to_bits() == y.to_bits()),
                "{w:?} add_scaled, n = {n}"
            );
            let (mut u0, mut u1) = (values(n, 4), values(n, 4));
            add_scaled_reversed_with(Width::Baseline, &mut u0, -1.3, &b);
            add_scaled_reversed_with(w, &mut u1, -1.3, &b);
            assert!(
                u0.iter().zip(&u1).all(|(x, y)| x.to_bits() == y.to_bits()),
                "{w:?} add_scaled_reversed, n = {n}"
            );
        }
    }
    eprintln!(
        "variants checked: {ran:?}; this processor runs {:?}",
        bem3d::wide::width()
    );
}
