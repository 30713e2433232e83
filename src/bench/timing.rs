//! Timing of one call: batches sized to a minimum duration, median of several batches.

use std::hint::black_box;
use std::time::{Duration, Instant};

/// How long to time one measurement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Budget {
    /// Minimum duration of one batch.
    pub batch: Duration,
    /// Number of batches; the median batch gives the figure.
    pub batches: usize,
}

impl Budget {
    /// The default budget: 5 batches of at least 20 ms.
    pub const NORMAL: Budget = Budget { batch: Duration::from_millis(20), batches: 5 };
    /// A smoke-run budget: 3 batches of at least 2 ms.
    pub const QUICK: Budget = Budget { batch: Duration::from_millis(2), batches: 3 };
}

/// Median nanoseconds per call of `f`.
pub fn ns_per_call<R>(budget: Budget, mut f: impl FnMut() -> R) -> f64 {
    // Size the batch: double the iteration count until one batch lasts long enough.
    let mut n: u64 = 1;
    loop {
        let t = Instant::now();
        for _ in 0..n {
            black_box(f());
        }
        if t.elapsed() >= budget.batch || n >= 1 << 30 {
            break;
        }
        n *= 2;
    }
    let mut per_call: Vec<f64> = (0..budget.batches.max(1))
        .map(|_| {
            let t = Instant::now();
            for _ in 0..n {
                black_box(f());
            }
            t.elapsed().as_nanos() as f64 / n as f64
        })
        .collect();
    per_call.sort_by(f64::total_cmp);
    per_call[per_call.len() / 2]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn longer_work_takes_longer() {
        let work = |k: u64| move || (0..k).fold(0u64, |a, i| a.wrapping_mul(31).wrapping_add(black_box(i)));
        let short = ns_per_call(Budget::QUICK, work(10));
        let long = ns_per_call(Budget::QUICK, work(10_000));
        assert!(short > 0.0 && long > 10.0 * short, "short {short} ns, long {long} ns");
    }
}
