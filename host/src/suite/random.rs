//! Seeded numbers and matrices for problem definitions: every random quantity of a suite
//! problem is a pure function of a 64-bit seed, itself derived from names and indices,
//! never from entropy or scheduling.

use hodr_core::Real;
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::SeedableRng;

/// splitmix64's finaliser: a bijection of u64 that spreads every input bit over the
/// output (Steele, Lea and Flood 2014).
pub fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A seed from a label and a list of integers: FNV-1a over the label's bytes, then each
/// integer folded in through [`mix`]. Equal inputs give equal seeds on every platform.
pub fn seed_of(label: &str, parts: &[u64]) -> u64 {
    let mut h: u64 = 0xCBF2_9CE4_8422_2325;
    for b in label.bytes() {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0000_0100_0000_01B3);
    }
    for &p in parts {
        h = mix(h ^ mix(p));
    }
    h
}

/// A seed from the bits of a point x: equal points, and only they (up to hash
/// collisions), give equal seeds.
pub fn point_seed(x: &[f64]) -> u64 {
    let bits: Vec<u64> = x.iter().map(|v| v.to_bits()).collect();
    seed_of("x", &bits)
}

/// A generator for `seed`.
pub fn rng(seed: u64) -> Xoshiro256PlusPlus {
    Xoshiro256PlusPlus::seed_from_u64(seed)
}

/// n numbers uniform in the open interval (lo, hi).
pub fn uniform(n: usize, lo: f64, hi: f64, seed: u64) -> Vec<f64> {
    let mut r = rng(seed);
    (0..n)
        .map(|_| lo + (hi - lo) * f64::uniform_open(&mut r))
        .collect()
}

/// n standard normal numbers (inverse-CDF transform of open uniforms).
pub fn gaussian(n: usize, seed: u64) -> Vec<f64> {
    let mut r = rng(seed);
    (0..n)
        .map(|_| f64::normal_quantile_open(f64::uniform_open(&mut r)))
        .collect()
}

/// A random n×n rotation, row-major: an n×n standard Gaussian matrix whose rows are
/// orthonormalised by modified Gram–Schmidt, run twice ("twice is enough", Giraud et
/// al. 2005) so that ‖RRᵀ − I‖ stays at rounding level for every n used here. The
/// rows of a Gaussian matrix are linearly independent with probability one; a row whose
/// norm vanishes after projection (a zero-probability event) is replaced by the first
/// unit vector eₑ whose part outside the rows before it has norm above ½/√n — one
/// always has: with P the projector onto their complement, Σₑ‖Peₑ‖² = tr P ≥ 1 — so
/// the result is always orthogonal.
pub fn rotation(n: usize, seed: u64) -> Vec<f64> {
    let g = gaussian(n * n, seed);
    let mut rows: Vec<Vec<f64>> = Vec::with_capacity(n);
    for i in 0..n {
        let mut v = g[i * n..(i + 1) * n].to_vec();
        if !orthonormalise(&mut v, &rows, 1e-8) {
            v = (0..n)
                .map(|e| {
                    let mut u = vec![0.0; n];
                    u[e] = 1.0;
                    u
                })
                .find_map(|mut u| {
                    orthonormalise(&mut u, &rows, 0.5 / (n as f64).sqrt()).then_some(u)
                })
                .unwrap_or_else(|| unreachable!("i < n rows cannot span every unit vector"));
        }
        rows.push(v);
    }
    rows.concat()
}

/// Removes from `v` its components along the orthonormal `rows` (modified Gram–Schmidt,
/// two passes) and normalises it; false, leaving `v` unusable, when the norm left is at
/// most `min_norm`.
fn orthonormalise(v: &mut [f64], rows: &[Vec<f64>], min_norm: f64) -> bool {
    for _pass in 0..2 {
        for r in rows {
            let d: f64 = v.iter().zip(r).map(|(a, b)| a * b).sum();
            for (a, b) in v.iter_mut().zip(r) {
                *a -= d * b;
            }
        }
    }
    let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    if norm <= min_norm {
        return false;
    }
    v.iter_mut().for_each(|a| *a /= norm);
    true
}

/// y = A x for a row-major n×n matrix A (`y.len() == x.len() == n`).
pub fn mat_vec(a: &[f64], x: &[f64], y: &mut [f64]) {
    let n = x.len();
    for (i, yi) in y.iter_mut().enumerate() {
        *yi = a[i * n..(i + 1) * n]
            .iter()
            .zip(x)
            .map(|(p, q)| p * q)
            .sum();
    }
}

/// The k-element index permutations of 0..k, each once (Heap's algorithm); k! of them.
pub fn permutations(k: usize) -> Vec<Vec<usize>> {
    let mut a: Vec<usize> = (0..k).collect();
    let mut out = vec![a.clone()];
    let mut c = vec![0usize; k];
    let mut i = 1;
    while i < k {
        if c[i] < i {
            if i % 2 == 0 {
                a.swap(0, i);
            } else {
                a.swap(c[i], i);
            }
            out.push(a.clone());
            c[i] += 1;
            i = 1;
        } else {
            c[i] = 0;
            i += 1;
        }
    }
    out
}
