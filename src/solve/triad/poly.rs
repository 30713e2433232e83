//! Small exact tools for the all-modes search: real trigonometric polynomials of degree
//! ≤ 4 as complex Fourier coefficients, their conversion to ordinary polynomials in
//! t = tan(φ/2), and real-root isolation of a polynomial of degree ≤ 6 on an interval by
//! the derivative sequence (between consecutive roots of p′ the polynomial is monotone,
//! so each sign change brackets exactly one root; a critical point where p is zero to
//! within rounding is a double root).

use nalgebra::Complex;

type C = Complex<f64>;

/// Highest harmonic kept.
pub const MAX_HARMONIC: usize = 4;
const N: usize = MAX_HARMONIC;

/// A real trigonometric polynomial Σ_{k=−N..N} c_k e^{ikφ} with c_{−k} = conj(c_k),
/// stored as `c[k + N]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Trig {
    c: [C; 2 * N + 1],
}

impl Trig {
    /// a + b·cos φ + s·sin φ.
    pub fn first(a: f64, b: f64, s: f64) -> Trig {
        let mut c = [C::new(0.0, 0.0); 2 * N + 1];
        c[N] = C::new(a, 0.0);
        c[N + 1] = C::new(0.5 * b, -0.5 * s);
        c[N - 1] = C::new(0.5 * b, 0.5 * s);
        Trig { c }
    }

    /// The coefficient c_k, k in −N..=N.
    #[cfg(test)]
    pub fn coeff(&self, k: i32) -> C {
        self.c[(k + N as i32) as usize]
    }

    /// Product; harmonics above N are dropped (callers keep the degree within N).
    pub fn mul(&self, o: &Trig) -> Trig {
        let mut c = [C::new(0.0, 0.0); 2 * N + 1];
        for (i, a) in self.c.iter().enumerate() {
            if *a == C::new(0.0, 0.0) {
                continue;
            }
            for (j, b) in o.c.iter().enumerate() {
                if *b == C::new(0.0, 0.0) {
                    continue;
                }
                let k = i as i32 + j as i32 - 2 * N as i32;
                if k.unsigned_abs() as usize <= N {
                    c[(k + N as i32) as usize] += a * b;
                }
            }
        }
        Trig { c }
    }

    /// Sum.
    pub fn add(&self, o: &Trig) -> Trig {
        let mut c = self.c;
        c.iter_mut().zip(o.c).for_each(|(a, b)| *a += b);
        Trig { c }
    }

    /// Difference.
    pub fn sub(&self, o: &Trig) -> Trig {
        let mut c = self.c;
        c.iter_mut().zip(o.c).for_each(|(a, b)| *a -= b);
        Trig { c }
    }

    /// Value at φ.
    #[cfg(test)]
    pub fn eval(&self, phi: f64) -> f64 {
        let mut s = self.c[N].re;
        for k in 1..=N {
            let (sin, cos) = libm::sincos(k as f64 * phi);
            let e = C::new(cos, sin);
            s += 2.0 * (self.c[N + k] * e).re;
        }
        s
    }

    /// The same function of ψ = φ − π (odd harmonics change sign).
    pub fn shifted_by_pi(&self) -> Trig {
        let mut c = self.c;
        for (i, v) in c.iter_mut().enumerate() {
            if (i as i32 - N as i32) % 2 != 0 {
                *v = -*v;
            }
        }
        Trig { c }
    }

    /// Sum of the magnitudes of the coefficients (a bound on |f| and a scale for rounding).
    /// `libm::hypot`, not `Complex::norm`: that is num-traits' `f64::hypot`, the platform's.
    pub fn magnitude(&self) -> f64 {
        self.c.iter().map(|v| libm::hypot(v.re, v.im)).sum()
    }

    /// The polynomial P(t) = (1 + t²)^3 · f(2·atan t), degree ≤ 6, coefficients in
    /// ascending powers; valid when harmonics above 3 are negligible (the caller checks).
    /// Uses e^{iφ} = (1 + it)/(1 − it).
    pub fn tan_half_poly(&self) -> [f64; 7] {
        // P(t) = c0 (1+it)^3 (1−it)^3 + Σ_{k=1..3} 2·Re(c_k (1+it)^{3+k} (1−it)^{3−k}):
        // the k < 0 terms are the conjugates of the k > 0 ones.
        let table = binomial_table();
        let mut out = [0.0; 7];
        for (k, row) in table.iter().enumerate() {
            let ck = self.c[N + k];
            let w = if k == 0 { 1.0 } else { 2.0 };
            for (o, v) in out.iter_mut().zip(row) {
                *o += w * (ck * v).re;
            }
        }
        out
    }
}

/// (1 + it)^{3+k} (1 − it)^{3−k} for k = 0..3, computed once.
fn binomial_table() -> &'static [[C; 7]; 4] {
    static TABLE: std::sync::OnceLock<[[C; 7]; 4]> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| [0, 1, 2, 3].map(|k| binomial_product(3 + k, 3 - k)))
}

/// Coefficients of (1 + it)^a (1 − it)^b (a + b = 6), ascending powers of t.
fn binomial_product(a: usize, b: usize) -> [C; 7] {
    let mut p = [C::new(0.0, 0.0); 7];
    p[0] = C::new(1.0, 0.0);
    let mut deg = 0;
    for (n, s) in [(a, 1.0), (b, -1.0)] {
        for _ in 0..n {
            // multiply by (1 + s·i·t)
            for k in (0..=deg + 1).rev() {
                let prev = if k > 0 { p[k - 1] } else { C::new(0.0, 0.0) };
                p[k] += prev * C::new(0.0, s);
            }
            deg += 1;
        }
    }
    p
}

/// Up to 16 sorted real numbers on the stack.
#[derive(Debug, Clone, Copy)]
pub struct Roots {
    v: [f64; 16],
    n: usize,
}

impl Roots {
    fn new() -> Roots {
        Roots { v: [0.0; 16], n: 0 }
    }

    fn push(&mut self, x: f64) {
        if self.n < self.v.len() {
            self.v[self.n] = x;
            self.n += 1;
        }
    }

    /// The roots, ascending.
    pub fn as_slice(&self) -> &[f64] {
        &self.v[..self.n]
    }

    fn sort(&mut self) {
        self.v[..self.n].sort_by(f64::total_cmp);
    }
}

fn eval(p: &[f64], x: f64) -> f64 {
    p.iter().rev().fold(0.0, |acc, &c| acc * x + c)
}

fn eval_abs(p: &[f64], x: f64) -> f64 {
    let ax = x.abs();
    p.iter().rev().fold(0.0, |acc, &c| acc * ax + c.abs())
}

fn eval_d(p: &[f64], x: f64) -> (f64, f64) {
    let mut v = 0.0;
    let mut d = 0.0;
    for &c in p.iter().rev() {
        d = d * x + v;
        v = v * x + c;
    }
    (v, d)
}

/// Real roots of the polynomial `p` (ascending coefficients, degree ≤ 6) in `[lo, hi]`,
/// ascending. Critical points where |p| ≤ `near_zero`·Σ|a_i||x|^i are reported as roots
/// too (double roots, or root pairs closer than rounding can separate), so a root pair is
/// never lost; callers verify each root. An identically zero polynomial has no roots here.
pub fn real_roots(p: &[f64], lo: f64, hi: f64, near_zero: f64) -> Roots {
    let mut deg = p.len();
    while deg > 0 && p[deg - 1] == 0.0 {
        deg -= 1;
    }
    let p = &p[..deg];
    let mut out = Roots::new();
    match deg {
        0 | 1 => return out,
        2 => {
            let x = -p[0] / p[1];
            if x >= lo && x <= hi {
                out.push(x);
            }
            return out;
        }
        _ => {}
    }
    let mut dp = [0.0; 6];
    for k in 1..deg {
        dp[k - 1] = k as f64 * p[k];
    }
    let crit = real_roots(&dp[..deg - 1], lo, hi, near_zero);
    let mut knots = [0.0; 18];
    let mut nk = 0;
    knots[nk] = lo;
    nk += 1;
    for &c in crit.as_slice() {
        if c > knots[nk - 1] && c < hi {
            knots[nk] = c;
            nk += 1;
        }
    }
    knots[nk] = hi;
    nk += 1;
    let mut values = [0.0; 18];
    for i in 0..nk {
        values[i] = eval(p, knots[i]);
    }
    for i in 0..nk {
        let (x, v) = (knots[i], values[i]);
        let interior = i > 0 && i + 1 < nk;
        if v == 0.0 || (interior && v.abs() <= near_zero * eval_abs(p, x)) {
            out.push(x);
        }
        if i + 1 < nk {
            let (y, w) = (knots[i + 1], values[i + 1]);
            if v != 0.0 && w != 0.0 && (v < 0.0) != (w < 0.0) {
                out.push(bracketed_root(p, x, y, v, w));
            }
        }
    }
    out.sort();
    out
}

/// Absolute accuracy of a bracketed root (the roots sought lie in |t| ≲ 1.2).
pub const ROOT_ABS_TOL: f64 = 4.0 * f64::EPSILON;

/// The single root of `p` in `[a, b]` where p changes sign (p monotone there): Newton
/// kept inside the bracket, bisection when a step leaves it.
fn bracketed_root(p: &[f64], mut a: f64, mut b: f64, fa: f64, fb: f64) -> f64 {
    let neg_at_a = fa < 0.0;
    // Start at the secant (regula falsi) point, inside the bracket.
    let s = a - fa * (b - a) / (fb - fa);
    let mut x = if s > a && s < b { s } else { 0.5 * (a + b) };
    for _ in 0..200 {
        let (v, d) = eval_d(p, x);
        if v == 0.0 {
            return x;
        }
        if (v < 0.0) == neg_at_a {
            a = x;
        } else {
            b = x;
        }
        if d != 0.0 {
            let newton = x - v / d;
            // The charts keep |t| ≲ 1.2, so an absolute tolerance of a few ulps of 1 is the
            // accuracy that matters (phi1 = 2·atan t).
            if (newton - x).abs() <= ROOT_ABS_TOL {
                return newton.clamp(a, b);
            }
            if newton > a && newton < b {
                x = newton;
                continue;
            }
        }
        if b - a <= ROOT_ABS_TOL {
            return 0.5 * (a + b);
        }
        x = 0.5 * (a + b);
    }
    x
}

#[cfg(test)]
#[allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the code under test calls"
)]
mod tests {
    use super::*;

    fn from_roots(r: &[f64]) -> Vec<f64> {
        let mut p = vec![1.0];
        for &x in r {
            let mut q = vec![0.0; p.len() + 1];
            for (k, c) in p.iter().enumerate() {
                q[k + 1] += c;
                q[k] -= c * x;
            }
            p = q;
        }
        p
    }

    #[test]
    fn finds_simple_and_close_roots() {
        let r = [-0.9, -0.3, 0.0001, 0.0002, 0.5, 0.99];
        let p = from_roots(&r);
        let got = real_roots(&p, -1.0, 1.0, 1e-12);
        assert_eq!(got.as_slice().len(), 6, "{:?}", got.as_slice());
        for (g, e) in got.as_slice().iter().zip(r) {
            assert!((g - e).abs() < 1e-12, "{g} vs {e}");
        }
        // Outside the interval: ignored.
        let got = real_roots(&from_roots(&[-2.0, 0.5, 3.0]), -1.0, 1.0, 1e-12);
        assert_eq!(got.as_slice(), &[0.5]);
    }

    #[test]
    fn a_double_root_is_reported() {
        let p = from_roots(&[-0.5, 0.25, 0.25, 0.7]);
        let got = real_roots(&p, -1.0, 1.0, 1e-12);
        assert!(got.as_slice().iter().any(|x| (x - 0.25).abs() < 1e-7), "{:?}", got.as_slice());
        // x² + 1 has none.
        assert!(real_roots(&[1.0, 0.0, 1.0], -1.0, 1.0, 1e-12).as_slice().is_empty());
    }

    #[test]
    fn tan_half_polynomial_matches_the_trig_polynomial() {
        let a = Trig::first(0.3, -1.2, 0.7);
        let b = Trig::first(-0.5, 0.4, 2.0);
        let c = Trig::first(1.5, 0.1, -0.6);
        let f = a.mul(&b).mul(&c).add(&a);
        let p = f.tan_half_poly();
        for t in [-0.9, -0.2, 0.0, 0.4, 1.0] {
            let phi = 2.0 * f64::atan(t);
            let lhs = eval(&p, t);
            let rhs = (1.0 + t * t).powi(3) * f.eval(phi);
            assert!((lhs - rhs).abs() < 1e-12, "t={t}: {lhs} vs {rhs}");
            let g = f.shifted_by_pi();
            assert!((g.eval(phi) - f.eval(phi + std::f64::consts::PI)).abs() < 1e-12);
        }
        // Direct check of first(): a + b cos + s sin.
        assert!((a.eval(0.8) - (0.3 - 1.2 * 0.8f64.cos() + 0.7 * 0.8f64.sin())).abs() < 1e-14);
    }
}
