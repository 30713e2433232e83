//! Streaming statistics of one quantity over the Monte Carlo's samples, mergeable exactly
//! ([`Tally`]): count, extremes, exact Σx and Σx² ([`ExactSum`]) and a histogram over a
//! range fixed before sampling, from which the percentiles are read. A run over all the
//! samples and the merge of its shards hold the same integers and extremes, so they give
//! the same statistics to the last bit.

use super::exact::ExactSum;

/// Streaming statistics of one quantity (a component's deviation from nominal at one
/// position).
#[derive(Debug, Clone, PartialEq)]
pub struct Tally {
    /// Samples counted.
    pub n: u64,
    /// Smallest sample (+∞ before the first).
    pub min: f64,
    /// Largest sample (−∞ before the first).
    pub max: f64,
    /// Σx, exact.
    pub sum: ExactSum,
    /// Σx² (each square rounded once), exact sum of those.
    pub squares: ExactSum,
    /// Left end of the histogram's range.
    pub lo: f64,
    /// Bin width (> 0).
    pub width: f64,
    /// Counts: below `lo`, then each bin, then at or above the range's right end.
    pub counts: Vec<u64>,
}

/// The statistics a [`Tally`] gives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Summary {
    /// Samples.
    pub n: u64,
    /// Mean.
    pub mean: f64,
    /// Standard deviation (n − 1).
    pub sigma: f64,
    /// Smallest and largest sample.
    pub min: f64,
    /// Largest sample.
    pub max: f64,
    /// The 0.135 % point (−3σ of a normal).
    pub p_low: f64,
    /// The 99.865 % point (+3σ of a normal).
    pub p_high: f64,
}

impl Tally {
    /// An empty tally with `bins` bins of equal width over [`lo`, `hi`] (`hi > lo`).
    pub fn new(lo: f64, hi: f64, bins: usize) -> Tally {
        let bins = bins.max(1);
        Tally {
            n: 0,
            min: f64::INFINITY,
            max: f64::NEG_INFINITY,
            sum: ExactSum::new(),
            squares: ExactSum::new(),
            lo,
            width: (hi - lo) / bins as f64,
            counts: vec![0; bins + 2],
        }
    }

    /// Number of bins inside the range.
    pub fn bins(&self) -> usize {
        self.counts.len() - 2
    }

    /// Counts `x` in the histogram and the extremes (the sums are added by the caller,
    /// a chunk's at a time: [`Tally::add_sums`]). `x` must be finite.
    #[inline]
    pub fn count(&mut self, x: f64) {
        self.n += 1;
        self.min = self.min.min(x);
        self.max = self.max.max(x);
        let u = (x - self.lo) / self.width;
        // NaN-free: x is finite and width > 0; below the range → 0, above → bins + 1.
        let i = if u < 0.0 { 0 } else { (u as usize).min(self.bins()) + 1 };
        self.counts[i] += 1;
    }

    /// Adds a chunk's Σx and Σx² (summed in the chunk's sample order).
    #[inline]
    pub fn add_sums(&mut self, sum: f64, squares: f64) {
        self.sum.add(sum);
        self.squares.add(squares);
    }

    /// Adds another tally over the same range (a thread's, a shard's): exact.
    pub fn merge(&mut self, o: &Tally) {
        self.n += o.n;
        self.min = self.min.min(o.min);
        self.max = self.max.max(o.max);
        self.sum.merge(&o.sum);
        self.squares.merge(&o.squares);
        for (a, b) in self.counts.iter_mut().zip(&o.counts) {
            *a += b;
        }
    }

    /// Mean, σ and the ±3σ percentiles; `None` before the first sample.
    pub fn summary(&self) -> Option<Summary> {
        if self.n == 0 {
            return None;
        }
        let n = self.n as f64;
        let (s1, s2) = (self.sum.value(), self.squares.value());
        let mean = s1 / n;
        let sigma = if self.n > 1 { ((s2 - s1 * mean) / (n - 1.0)).max(0.0).sqrt() } else { 0.0 };
        Some(Summary {
            n: self.n,
            mean,
            sigma,
            min: self.min,
            max: self.max,
            p_low: self.percentile(0.135),
            p_high: self.percentile(99.865),
        })
    }

    /// The `p` % point of the histogram: the samples of each bin spread evenly over it (the
    /// ones below the range over [min, lo], the ones above over [hi, max]), the point where
    /// p % of them lie below, within [min, max].
    pub fn percentile(&self, p: f64) -> f64 {
        if self.n == 0 {
            return f64::NAN;
        }
        let target = (p / 100.0).clamp(0.0, 1.0) * self.n as f64;
        let hi = self.lo + self.width * self.bins() as f64;
        let mut below = 0.0;
        for (i, &c) in self.counts.iter().enumerate() {
            if c == 0 {
                continue;
            }
            let c = c as f64;
            if below + c >= target {
                let (a, b) = match i {
                    0 => (self.min, self.lo.min(self.max)),
                    i if i == self.counts.len() - 1 => (hi.max(self.min), self.max),
                    i => (self.lo + self.width * (i - 1) as f64, self.lo + self.width * i as f64),
                };
                let x = a + (b - a) * ((target - below) / c);
                return x.clamp(self.min, self.max);
            }
            below += c;
        }
        self.max
    }

    /// The histogram of the samples inside the range: left edge, bin width, counts.
    pub fn histogram(&self) -> (f64, f64, &[u64]) {
        (self.lo, self.width, &self.counts[1..self.counts.len() - 1])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percentiles_of_an_even_spread_are_its_quantiles() {
        // 0.5, 1.5, … 99.5 over [0, 100) in 100 bins: the p % point is p.
        let mut t = Tally::new(0.0, 100.0, 100);
        for i in 0..100 {
            let x = i as f64 + 0.5;
            t.count(x);
            t.add_sums(x, x * x);
        }
        for p in [10.0, 50.0, 90.0] {
            assert!((t.percentile(p) - p).abs() < 1e-9, "{p}: {}", t.percentile(p));
        }
        let s = t.summary().unwrap();
        assert!((s.mean - 50.0).abs() < 1e-12);
        // σ of 0.5..99.5 step 1 (n − 1): sqrt(100·101/12) ≈ 29.01
        assert!((s.sigma - (100.0f64 * 101.0 / 12.0).sqrt()).abs() < 1e-9);
        assert_eq!((s.min, s.max), (0.5, 99.5));
    }

    #[test]
    fn samples_outside_the_range_are_counted_and_the_extremes_bound_the_percentiles() {
        let mut t = Tally::new(-1.0, 1.0, 10);
        for x in [-5.0, 0.0, 0.1, 3.0] {
            t.count(x);
        }
        assert_eq!(t.counts[0], 1);
        assert_eq!(t.counts[11], 1);
        assert_eq!(t.percentile(0.0), -5.0);
        assert_eq!(t.percentile(100.0), 3.0);
        // Merging two halves gives the whole.
        let (mut a, mut b) = (Tally::new(-1.0, 1.0, 10), Tally::new(-1.0, 1.0, 10));
        for x in [-5.0, 0.0] {
            a.count(x);
        }
        for x in [0.1, 3.0] {
            b.count(x);
        }
        a.merge(&b);
        assert_eq!(a, t);
    }
}
