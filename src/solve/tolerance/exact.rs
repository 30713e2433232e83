//! Exact sums of doubles, independent of the order of the additions: what lets the Monte
//! Carlo's shards merge into the bits of one run ([`ExactSum`]).

/// Digits of 32 bits; digit k weighs 2^(32k − 1074), so the lowest bit is the smallest
/// subnormal double and 67 digits reach past 2^1024 with one to spare for the sign.
const LIMBS: usize = 68;
/// Bits per digit.
const DIGIT: u32 = 32;
/// Additions an accumulator takes before its carries are propagated: each adds less than
/// 2^32 to a digit held in an i64.
const PENDING_MAX: u32 = 1 << 30;

/// An exact sum of finite doubles: a fixed-point integer in units of 2^−1074 (the smallest
/// subnormal) held as base-2^32 digits in i64 limbs, with room for 2^30 additions between
/// carry propagations. Adding is exact, so the sum is the same integer whatever the order
/// of the additions or the grouping of partial sums ([`ExactSum::merge`]); [`ExactSum::value`]
/// is a function of that integer alone (correctly rounded to the nearest double except in
/// the subnormal range, where it may be one unit off), hence equal bits for equal sums.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ExactSum {
    limbs: [i64; LIMBS],
    pending: u32,
}

impl Default for ExactSum {
    fn default() -> ExactSum {
        ExactSum { limbs: [0; LIMBS], pending: 0 }
    }
}

impl ExactSum {
    /// Zero.
    pub fn new() -> ExactSum {
        ExactSum::default()
    }

    /// Adds `x` exactly. Non-finite values are the caller's to keep out (they are ignored).
    #[inline]
    pub fn add(&mut self, x: f64) {
        if x == 0.0 || !x.is_finite() {
            return;
        }
        if self.pending >= PENDING_MAX {
            self.normalize();
        }
        self.pending += 1;
        let bits = x.to_bits();
        let raw_exp = ((bits >> 52) & 0x7ff) as u32;
        let frac = bits & ((1u64 << 52) - 1);
        // value = m · 2^(shift − 1074)
        let (m, shift) = if raw_exp == 0 { (frac, 0) } else { (frac | (1u64 << 52), raw_exp - 1) };
        let k = (shift / DIGIT) as usize;
        let v = u128::from(m) << (shift % DIGIT);
        let digits = [(v & 0xffff_ffff) as i64, ((v >> 32) & 0xffff_ffff) as i64, (v >> 64) as i64];
        let negative = x < 0.0;
        for (j, d) in digits.into_iter().enumerate() {
            if d != 0 {
                // k + 2 ≤ 66 < LIMBS for every finite double.
                self.limbs[k + j] += if negative { -d } else { d };
            }
        }
    }

    /// Adds another exact sum (a shard's, a thread's): exact, so the grouping of partial
    /// sums does not change the total.
    pub fn merge(&mut self, other: &ExactSum) {
        self.normalize();
        let mut o = other.clone();
        o.normalize();
        for (a, b) in self.limbs.iter_mut().zip(o.limbs) {
            *a += b;
        }
        self.pending = 1;
        self.normalize();
    }

    /// Propagates the carries: every digit below the top in [0, 2^32), the top one signed.
    /// The representation is then unique for each integer.
    fn normalize(&mut self) {
        for k in 0..LIMBS - 1 {
            let carry = self.limbs[k] >> DIGIT;
            self.limbs[k] -= carry << DIGIT;
            self.limbs[k + 1] += carry;
        }
        self.pending = 0;
    }

    /// The sum as the nearest double (see the type's notes on the subnormal range).
    pub fn value(&self) -> f64 {
        let mut s = self.clone();
        s.normalize();
        let negative = s.limbs[LIMBS - 1] < 0;
        if negative {
            for l in &mut s.limbs {
                *l = -*l;
            }
            s.normalize();
        }
        let Some(top) = s.limbs.iter().rposition(|&l| l != 0) else { return 0.0 };
        // The top three digits (up to 96 bits), the rest as a sticky bit: OR-ing a 1 below
        // the 53 kept bits breaks a tie the way the exact value does.
        let low = top.saturating_sub(2);
        let mut mant: u128 = 0;
        for k in (low..=top).rev() {
            mant = (mant << DIGIT) | s.limbs[k] as u128;
        }
        if s.limbs[..low].iter().any(|&l| l != 0) {
            mant |= 1;
        }
        let v = libm::scalbn(mant as f64, (DIGIT as usize * low) as i32 - 1074);
        if negative { -v } else { v }
    }

    /// The normalised digits as `(index, digit)` pairs, nonzero ones only (the form a shard
    /// file keeps).
    pub fn digits(&self) -> Vec<(u8, i64)> {
        let mut s = self.clone();
        s.normalize();
        s.limbs.iter().enumerate().filter(|(_, l)| **l != 0).map(|(k, l)| (k as u8, *l)).collect()
    }

    /// The sum with these digits (as [`ExactSum::digits`] gives them); `None` when an index
    /// is out of range or a digit below the top is outside [0, 2^32).
    pub fn from_digits(digits: &[(u8, i64)]) -> Option<ExactSum> {
        let mut s = ExactSum::new();
        for &(k, l) in digits {
            let k = usize::from(k);
            if k >= LIMBS || (k < LIMBS - 1 && !(0..1i64 << DIGIT).contains(&l)) {
                return None;
            }
            s.limbs[k] = l;
        }
        Some(s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngExt, SeedableRng};

    #[test]
    fn sums_are_exact_and_independent_of_order() {
        // 1e16 + 1 − 1e16 loses the 1 in doubles; the exact sum keeps it.
        let mut s = ExactSum::new();
        for x in [1e16, 1.0, -1e16] {
            s.add(x);
        }
        assert_eq!(s.value(), 1.0);
        // Widely spread magnitudes and signs, summed in two orders and in two halves.
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        let xs: Vec<f64> = (0..5000)
            .map(|_| {
                let e: i32 = rng.random_range(-40..20);
                let m: f64 = rng.random::<f64>() - 0.5;
                m * crate::geom::powi(2.0, e)
            })
            .collect();
        let (mut a, mut b, mut h1, mut h2) = (ExactSum::new(), ExactSum::new(), ExactSum::new(), ExactSum::new());
        xs.iter().for_each(|&x| a.add(x));
        xs.iter().rev().for_each(|&x| b.add(x));
        xs[..1234].iter().for_each(|&x| h1.add(x));
        xs[1234..].iter().for_each(|&x| h2.add(x));
        h2.merge(&h1);
        assert_eq!(a.value().to_bits(), b.value().to_bits());
        assert_eq!(a.value().to_bits(), h2.value().to_bits());
        assert_eq!(a.digits(), h2.digits());
        // Against a sum in i128 fixed point (every value is a multiple of 2^-93 here and
        // the total stays far below 2^127 units).
        let unit = crate::geom::powi(2.0, -93);
        let fixed: i128 = xs.iter().map(|&x| (x / unit) as i128).sum();
        let want = fixed as f64 * unit;
        assert_eq!(a.value(), want);
    }

    #[test]
    fn negative_small_and_extreme_values_round_trip() {
        for x in [-3.5, 5e-324, -5e-324, f64::MAX, -f64::MAX, 1.0 / 3.0, -2.2250738585072014e-308] {
            let mut s = ExactSum::new();
            s.add(x);
            assert_eq!(s.value(), x, "{x}");
            let back = ExactSum::from_digits(&s.digits()).unwrap();
            assert_eq!(back.value(), x);
        }
        let mut s = ExactSum::new();
        s.add(1.0);
        s.add(-1.0);
        assert_eq!(s.value(), 0.0);
        assert!(ExactSum::from_digits(&[(80, 1)]).is_none());
        assert!(ExactSum::from_digits(&[(3, -1)]).is_none());
    }

    #[test]
    fn ties_round_to_even_as_the_exact_value_says() {
        // 1 + 2^-53 is a tie: it rounds to 1 (even); a tiny bit more rounds up.
        let mut s = ExactSum::new();
        s.add(1.0);
        s.add(crate::geom::powi(2.0, -53));
        assert_eq!(s.value(), 1.0);
        s.add(crate::geom::powi(2.0, -200));
        assert_eq!(s.value(), 1.0 + f64::EPSILON);
    }
}
