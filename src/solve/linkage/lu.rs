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

    /// Solves Aᵀ·x = b in place with the same factorisation (P·A = L·U, so
    /// Aᵀ = Uᵀ·Lᵀ·P: forward with Uᵀ, back with the unit Lᵀ, then the row swaps undone in
    /// reverse order). The kineto-statics' one extra solve per sample.
    pub(super) fn solve_transposed(&self, b: &mut [f64]) {
        let n = self.n;
        let a = &self.a;
        for r in 0..n {
            let mut s = b[r];
            for k in 0..r {
                s -= a[k * n + r] * b[k];
            }
            b[r] = s / a[r * n + r];
        }
        for r in (0..n).rev() {
            let mut s = b[r];
            for k in r + 1..n {
                s -= a[k * n + r] * b[k];
            }
            b[r] = s;
        }
        for k in (0..n).rev() {
            b.swap(k, self.piv[k]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn transposed_solve_inverts_the_transpose() {
        // A matrix that needs row swaps (zero leading entry).
        let m = [0.0, 2.0, 1.0, 3.0, 1.0, -1.0, 1.0, 4.0, 2.0];
        let mut lu = Lu::new(3);
        lu.a.copy_from_slice(&m);
        assert!(lu.factor(1.0));
        let x = [1.5, -2.0, 0.25];
        // b = Aᵀ·x
        let mut b: Vec<f64> = (0..3).map(|c| (0..3).map(|r| m[r * 3 + c] * x[r]).sum()).collect();
        lu.solve_transposed(&mut b);
        for (got, want) in b.iter().zip(x) {
            assert!((got - want).abs() < 1e-14, "{b:?}");
        }
        // and the plain solve still inverts A.
        let mut c: Vec<f64> = (0..3).map(|r| (0..3).map(|k| m[r * 3 + k] * x[k]).sum()).collect();
        lu.solve(&mut c);
        for (got, want) in c.iter().zip(x) {
            assert!((got - want).abs() < 1e-14, "{c:?}");
        }
    }
}
