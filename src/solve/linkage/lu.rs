//! Dense LU factorisation with partial pivoting for the linkage solver.

use super::SINGULAR_PIVOT_REL;

/// Dense LU with partial pivoting, in place, allocation-free after construction.
/// (nalgebra's `LU` takes its matrix by value, which would allocate on every step.)
#[derive(Debug, Clone)]
pub(super) struct Lu {
    pub(super) n: usize,
    pub(super) a: Vec<f64>,
    pub(super) piv: Vec<usize>,
    /// Smallest pivot of the last factorisation relative to the `scale` it was given.
    pub(super) min_pivot_rel: f64,
}

impl Lu {
    pub(super) fn new(n: usize) -> Lu {
        Lu { n, a: vec![0.0; n * n], piv: vec![0; n], min_pivot_rel: f64::INFINITY }
    }

    /// Factors the row-major matrix in `self.a`; false if a pivot falls below
    /// `SINGULAR_PIVOT_REL · scale`. Records the smallest pivot / `scale` in `min_pivot_rel`.
    pub(super) fn factor(&mut self, scale: f64) -> bool {
        let n = self.n;
        let a = &mut self.a;
        self.min_pivot_rel = f64::INFINITY;
        for k in 0..n {
            let mut p = k;
            let mut best = a[k * n + k].abs();
            for r in k + 1..n {
                let v = a[r * n + k].abs();
                if v > best {
                    best = v;
                    p = r;
                }
            }
            self.min_pivot_rel = self.min_pivot_rel.min(best / scale);
            if best <= SINGULAR_PIVOT_REL * scale || !best.is_finite() {
                return false;
            }
            self.piv[k] = p;
            if p != k {
                let (upper, lower) = a.split_at_mut(p * n);
                upper[k * n..(k + 1) * n].swap_with_slice(&mut lower[..n]);
            }
            let (top, bottom) = a.split_at_mut((k + 1) * n);
            let pivot_row = &top[k * n..];
            let inv = 1.0 / pivot_row[k];
            for row in bottom.chunks_exact_mut(n) {
                let f = row[k] * inv;
                row[k] = f;
                if f != 0.0 {
                    for (x, y) in row[k + 1..].iter_mut().zip(&pivot_row[k + 1..]) {
                        *x -= f * y;
                    }
                }
            }
        }
        true
    }

    /// Solves A·x = b in place.
    pub(super) fn solve(&self, b: &mut [f64]) {
        let n = self.n;
        let a = &self.a;
        for k in 0..n {
            b.swap(k, self.piv[k]);
        }
        for r in 1..n {
            let row = &a[r * n..r * n + r];
            let s: f64 = row.iter().zip(&b[..r]).map(|(x, y)| x * y).sum();
            b[r] -= s;
        }
        for r in (0..n).rev() {
            let row = &a[r * n + r + 1..(r + 1) * n];
            let s: f64 = row.iter().zip(&b[r + 1..n]).map(|(x, y)| x * y).sum();
            b[r] = (b[r] - s) / a[r * n + r];
        }
    }
}
