//! Numbers for closed forms written once and run on one time step or on four at a time:
//! [`Real`] is `f64` (a step) or [`F4`] (four steps in the lanes of SIMD registers). Every
//! operation is lane by lane and correctly rounded (+, −, ×, ÷, √ as IEEE 754 defines them,
//! never fused), so a closed form written over `Real` gives the same bits in each lane of
//! `F4` as over `f64` — the sweep's four steps at a time are the step's own numbers.

use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

use wide::f64x4;

/// A number a closed form computes with: one step's `f64`, or four steps' [`F4`].
pub(super) trait Real:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self> + Neg<Output = Self>
{
    /// Which lanes a comparison holds in: `bool`, or [`M4`].
    type Mask: Copy + BitAnd<Output = Self::Mask> + BitOr<Output = Self::Mask> + Not<Output = Self::Mask>;
    /// `v` in every lane.
    fn splat(v: f64) -> Self;
    /// The correctly rounded square root.
    fn sqrt(self) -> Self;
    /// |x|.
    fn abs(self) -> Self;
    /// x < y, x ≤ y, x > y, x ≥ y (false where either is NaN).
    fn lt(self, o: Self) -> Self::Mask;
    fn le(self, o: Self) -> Self::Mask;
    fn gt(self, o: Self) -> Self::Mask;
    fn ge(self, o: Self) -> Self::Mask;
    /// `a` in the lanes of `m`, `b` in the others.
    fn select(m: Self::Mask, a: Self, b: Self) -> Self;
    /// The mask `v` in every lane.
    fn mask(v: bool) -> Self::Mask;
}

impl Real for f64 {
    type Mask = bool;
    #[inline(always)]
    fn splat(v: f64) -> f64 {
        v
    }
    #[inline(always)]
    fn sqrt(self) -> f64 {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn abs(self) -> f64 {
        f64::abs(self)
    }
    #[inline(always)]
    fn lt(self, o: f64) -> bool {
        self < o
    }
    #[inline(always)]
    fn le(self, o: f64) -> bool {
        self <= o
    }
    #[inline(always)]
    fn gt(self, o: f64) -> bool {
        self > o
    }
    #[inline(always)]
    fn ge(self, o: f64) -> bool {
        self >= o
    }
    #[inline(always)]
    fn select(m: bool, a: f64, b: f64) -> f64 {
        if m { a } else { b }
    }
    #[inline(always)]
    fn mask(v: bool) -> bool {
        v
    }
}

/// Four f64 lanes (four time steps).
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct F4(f64x4);

/// A load or store of four lanes from a slice of `len` values (a caller's bug).
#[cold]
#[inline(never)]
fn too_short(len: usize) -> ! {
    panic!("four lanes from a slice of {len} values")
}

/// A lane mask of [`F4`]: all bits set where true.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct M4(f64x4);

impl F4 {
    /// The four values from `s[0..4]`.
    #[inline(always)]
    pub(super) fn load(s: &[f64]) -> F4 {
        match s.first_chunk::<4>() {
            Some(v) => F4(f64x4::new(*v)),
            None => too_short(s.len()),
        }
    }
    /// Writes the four values into `s[0..4]`.
    #[inline(always)]
    pub(super) fn store(self, s: &mut [f64]) {
        let n = s.len();
        match s.first_chunk_mut::<4>() {
            Some(v) => *v = self.0.to_array(),
            None => too_short(n),
        }
    }
    /// The lanes as an array.
    #[inline(always)]
    pub(super) fn to_array(self) -> [f64; 4] {
        self.0.to_array()
    }
    /// The lanes of an array.
    #[inline(always)]
    pub(super) fn new(v: [f64; 4]) -> F4 {
        F4(f64x4::new(v))
    }
}

impl M4 {
    /// Bit i set where lane i is true.
    #[inline(always)]
    pub(super) fn bits(self) -> u32 {
        self.0.to_bitmask()
    }
}

macro_rules! lanewise {
    ($($tr:ident $f:ident $t:ty;)*) => {$(
        impl $tr for $t {
            type Output = $t;
            #[inline(always)]
            fn $f(self, o: $t) -> $t {
                Self($tr::$f(self.0, o.0))
            }
        }
    )*};
}

lanewise! {
    Add add F4;
    Sub sub F4;
    Mul mul F4;
    Div div F4;
    BitAnd bitand M4;
    BitOr bitor M4;
}

impl Neg for F4 {
    type Output = F4;
    #[inline(always)]
    fn neg(self) -> F4 {
        F4(-self.0)
    }
}

impl Not for M4 {
    type Output = M4;
    #[inline(always)]
    fn not(self) -> M4 {
        M4(!self.0)
    }
}

impl Real for F4 {
    type Mask = M4;
    #[inline(always)]
    fn splat(v: f64) -> F4 {
        F4(f64x4::splat(v))
    }
    #[inline(always)]
    fn sqrt(self) -> F4 {
        F4(self.0.sqrt())
    }
    #[inline(always)]
    fn abs(self) -> F4 {
        F4(self.0.abs())
    }
    #[inline(always)]
    fn lt(self, o: F4) -> M4 {
        M4(self.0.simd_lt(o.0))
    }
    #[inline(always)]
    fn le(self, o: F4) -> M4 {
        M4(self.0.simd_le(o.0))
    }
    #[inline(always)]
    fn gt(self, o: F4) -> M4 {
        M4(self.0.simd_gt(o.0))
    }
    #[inline(always)]
    fn ge(self, o: F4) -> M4 {
        M4(self.0.simd_ge(o.0))
    }
    #[inline(always)]
    fn select(m: M4, a: F4, b: F4) -> F4 {
        F4(m.0.select(a.0, b.0))
    }
    #[inline(always)]
    fn mask(v: bool) -> M4 {
        M4(f64x4::splat(f64::from_bits(if v { u64::MAX } else { 0 })))
    }
}

/// A [`Real`] read from and written to consecutive time steps: `f64` one step, [`F4`]
/// four.
pub(super) trait Lanes: Real {
    /// Steps per value.
    const N: usize;
    /// The values of `s[0..N]`.
    fn load(s: &[f64]) -> Self;
    /// Writes the values into `s[0..N]`.
    fn store(self, s: &mut [f64]);
    /// Lane i from `f(i)`.
    fn gather(f: impl FnMut(usize) -> f64) -> Self;
    /// Lane by lane, the pair `f` gives for each value.
    fn map2(self, f: impl FnMut(f64) -> (f64, f64)) -> (Self, Self);
    /// The first lane where `m` is false (`None`: true in every lane).
    fn first_false(m: Self::Mask) -> Option<usize>;
    /// The first lane where `m` is true.
    fn first_true(m: Self::Mask) -> Option<usize>;
    /// In the lanes where `m` is false, `f(i)` instead.
    fn patch(self, m: Self::Mask, f: impl FnMut(usize) -> f64) -> Self;
    /// Lane `i`.
    fn lane(self, i: usize) -> f64;
}

impl Lanes for f64 {
    const N: usize = 1;
    #[inline(always)]
    fn load(s: &[f64]) -> f64 {
        s[0]
    }
    #[inline(always)]
    fn store(self, s: &mut [f64]) {
        s[0] = self;
    }
    #[inline(always)]
    fn gather(mut f: impl FnMut(usize) -> f64) -> f64 {
        f(0)
    }
    #[inline(always)]
    fn map2(self, mut f: impl FnMut(f64) -> (f64, f64)) -> (f64, f64) {
        f(self)
    }
    #[inline(always)]
    fn first_false(m: bool) -> Option<usize> {
        (!m).then_some(0)
    }
    #[inline(always)]
    fn first_true(m: bool) -> Option<usize> {
        m.then_some(0)
    }
    #[inline(always)]
    fn patch(self, m: bool, mut f: impl FnMut(usize) -> f64) -> f64 {
        if m { self } else { f(0) }
    }
    #[inline(always)]
    fn lane(self, _: usize) -> f64 {
        self
    }
}

impl Lanes for F4 {
    const N: usize = 4;
    #[inline(always)]
    fn load(s: &[f64]) -> F4 {
        F4::load(s)
    }
    #[inline(always)]
    fn store(self, s: &mut [f64]) {
        F4::store(self, s)
    }
    #[inline(always)]
    fn gather(f: impl FnMut(usize) -> f64) -> F4 {
        F4::new(std::array::from_fn(f))
    }
    #[inline(always)]
    fn map2(self, mut f: impl FnMut(f64) -> (f64, f64)) -> (F4, F4) {
        let v = self.to_array().map(&mut f);
        (F4::new(v.map(|p| p.0)), F4::new(v.map(|p| p.1)))
    }
    #[inline(always)]
    fn first_false(m: M4) -> Option<usize> {
        let missing = !m.bits() & 0b1111;
        (missing != 0).then(|| missing.trailing_zeros() as usize)
    }
    #[inline(always)]
    fn first_true(m: M4) -> Option<usize> {
        let bits = m.bits();
        (bits != 0).then(|| bits.trailing_zeros() as usize)
    }
    #[inline(always)]
    fn patch(self, m: M4, f: impl FnMut(usize) -> f64) -> F4 {
        if m.bits() == 0b1111 { self } else { patch_lanes(self, m, f) }
    }
    #[inline(always)]
    fn lane(self, i: usize) -> f64 {
        self.to_array()[i]
    }
}

/// [`Lanes::patch`] of the rare lanes, out of the hot loop.
#[cold]
#[inline(never)]
fn patch_lanes(v: F4, m: M4, mut f: impl FnMut(usize) -> f64) -> F4 {
    let mut out = v.to_array();
    let bits = m.bits();
    for (i, o) in out.iter_mut().enumerate() {
        if bits & (1 << i) == 0 {
            *o = f(i);
        }
    }
    F4::new(out)
}

/// A 2-vector of [`Real`]s: one step's point or direction, or four steps'.
#[derive(Debug, Clone, Copy)]
pub(super) struct V2<T> {
    pub(super) x: T,
    pub(super) y: T,
}

impl<T: Real> V2<T> {
    #[inline(always)]
    pub(super) fn new(x: T, y: T) -> V2<T> {
        V2 { x, y }
    }
    /// The constant vector `v` in every lane.
    #[inline(always)]
    pub(super) fn splat(v: crate::geom::Vector) -> V2<T> {
        V2 { x: T::splat(v.x), y: T::splat(v.y) }
    }
    /// a·b (x·x′ + y·y′, as nalgebra's dot of 2-vectors).
    #[inline(always)]
    pub(super) fn dot(self, o: V2<T>) -> T {
        self.x * o.x + self.y * o.y
    }
    /// |a|² (the dot with itself).
    #[inline(always)]
    pub(super) fn norm_squared(self) -> T {
        self.dot(self)
    }
    /// The z-component of a × b.
    #[inline(always)]
    pub(super) fn cross(self, o: V2<T>) -> T {
        self.x * o.y - self.y * o.x
    }
    /// Turned by +90°.
    #[inline(always)]
    pub(super) fn perp(self) -> V2<T> {
        V2 { x: -self.y, y: self.x }
    }
    /// Each coordinate times `k`.
    #[inline(always)]
    pub(super) fn scale(self, k: T) -> V2<T> {
        V2 { x: self.x * k, y: self.y * k }
    }
    /// Rotated by the rotation (cos, sin) `cs`.
    #[inline(always)]
    pub(super) fn rot(self, (c, s): (T, T)) -> V2<T> {
        V2 { x: c * self.x - s * self.y, y: s * self.x + c * self.y }
    }
}

impl<T: Real> Add for V2<T> {
    type Output = V2<T>;
    #[inline(always)]
    fn add(self, o: V2<T>) -> V2<T> {
        V2 { x: self.x + o.x, y: self.y + o.y }
    }
}

impl<T: Real> Sub for V2<T> {
    type Output = V2<T>;
    #[inline(always)]
    fn sub(self, o: V2<T>) -> V2<T> {
        V2 { x: self.x - o.x, y: self.y - o.y }
    }
}

impl<T: Real> Neg for V2<T> {
    type Output = V2<T>;
    #[inline(always)]
    fn neg(self) -> V2<T> {
        V2 { x: -self.x, y: -self.y }
    }
}

impl From<crate::geom::Vector> for V2<f64> {
    #[inline(always)]
    fn from(v: crate::geom::Vector) -> V2<f64> {
        V2 { x: v.x, y: v.y }
    }
}

impl From<V2<f64>> for crate::geom::Vector {
    #[inline(always)]
    fn from(v: V2<f64>) -> crate::geom::Vector {
        crate::geom::Vector::new(v.x, v.y)
    }
}

/// The rotation by a then b: (cos, sin) of the sum of their angles.
#[inline(always)]
pub(super) fn compose<T: Real>(a: (T, T), b: (T, T)) -> (T, T) {
    (a.0 * b.0 - a.1 * b.1, a.1 * b.0 + a.0 * b.1)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Awkward numbers: signed zeros, subnormals, huge, tiny, infinities, NaN, and ordinary
    /// values of every sign.
    const ODD: [f64; 16] = [
        0.0,
        -0.0,
        1.0,
        -1.5,
        1e-310,
        -3e-320,
        1.7976931348623157e308,
        -1e300,
        1e-300,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
        0.1,
        -2.0 / 3.0,
        123456.789,
        std::f64::consts::PI,
    ];

    #[test]
    fn four_lanes_give_the_bits_of_one_step_each() {
        let lanes = |f: &dyn Fn(F4, F4) -> F4, g: &dyn Fn(f64, f64) -> f64| {
            for a in ODD.chunks_exact(4) {
                for &b0 in &ODD {
                    let b = [b0, -b0, b0 * 0.5, 1.0 / b0];
                    let got = f(F4::load(a), F4::new(b)).to_array();
                    for i in 0..4 {
                        let want = g(std::hint::black_box(a[i]), std::hint::black_box(b[i]));
                        // A NaN is a NaN (its sign and payload are the hardware's, and a value
                        // the compiler folds gets another).
                        if want.is_nan() {
                            assert!(got[i].is_nan(), "lane {i}: {} and {}: {} for NaN", a[i], b[i], got[i]);
                        } else {
                            assert_eq!(got[i].to_bits(), want.to_bits(), "lane {i}: {} and {}", a[i], b[i]);
                        }
                    }
                }
            }
        };
        lanes(&|a, b| a + b, &|a, b| a + b);
        lanes(&|a, b| a - b, &|a, b| a - b);
        lanes(&|a, b| a * b, &|a, b| a * b);
        lanes(&|a, b| a / b, &|a, b| a / b);
        lanes(&|a, _| -a, &|a, _| -a);
        lanes(&|a, _| a.sqrt(), &|a, _| a.sqrt());
        lanes(&|a, _| Real::abs(a), &|a, _| a.abs());
        type Cmp = fn(f64, f64) -> bool;
        type Cmp4 = fn(F4, F4) -> M4;
        let cmps: [(Cmp4, Cmp); 4] =
            [(Real::lt, |a, b| a < b), (Real::le, |a, b| a <= b), (Real::gt, |a, b| a > b), (Real::ge, |a, b| a >= b)];
        for (f, g) in cmps {
            lanes(&|a, b| F4::select(f(a, b), a, b), &|a, b| if g(a, b) { a } else { b });
            lanes(&|a, b| F4::select(!f(a, b) & f(b, a), a, b), &|a, b| if !g(a, b) && g(b, a) { a } else { b });
            lanes(&|a, b| F4::select(f(a, b) | f(b, a), a, b), &|a, b| if g(a, b) || g(b, a) { a } else { b });
        }
    }

    #[test]
    fn a_mask_tells_its_lanes() {
        let m = F4::new([1.0, -1.0, f64::NAN, 2.0]).gt(F4::splat(0.0));
        assert_eq!(m.bits(), 0b1001);
        assert_eq!(F4::splat(f64::NAN).ge(F4::splat(0.0)).bits(), 0);
    }
}
