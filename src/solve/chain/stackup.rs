//! Tolerance stack-up of a dimensional function Z = Σ c_i·w_i.
//!
//! Each independent dimension's size deviates by d_i ∈ [lower_i, upper_i]; its signed value
//! is w_i = nominal_i + s_i·d_i with s_i the sign of the nominal. An asymmetric band is a
//! mean shift m_i = (upper_i + lower_i)/2 plus a symmetric half-band t_i = (upper_i − lower_i)/2,
//! so with k_i = c_i·s_i:
//!
//! - mean of Z = Z_nominal + Σ k_i·m_i
//! - worst case: mean ± Σ t_i
//! - RSS: mean ± sqrt(Σ t_i²) (every t_i taken as 3σ)
//! - modified RSS: mean ± f·RSS, never beyond the worst case
//! - Monte Carlo: d_i = m_i + e_i with e_i drawn from the scene's distribution on
//!   [−t_i, t_i] (normal with 3σ = t_i, uniform, symmetric triangular).

use crate::par::prelude::*;
use rand::distr::Distribution as _;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;

use super::graph::Function;
use super::model::{Dimension, Distribution};

/// Samples drawn from one random stream; stream k of the seed draws chunk k, so the
/// result does not depend on the number of threads.
pub const CHUNK: usize = 1 << 15;
/// Percentiles reported by the Monte Carlo, in percent: ±3σ, ±2σ (95 %), median.
pub const PERCENTILES: [f64; 5] = [0.135, 2.5, 50.0, 97.5, 99.865];

/// One independent dimension's part in a dependent dimension's tolerance.
#[derive(Debug, Clone, PartialEq)]
pub struct Contribution {
    /// Index of the dimension.
    pub dim: usize,
    /// Coefficient in the function (±1).
    pub coef: f64,
    /// Half-band t_i (the ± tolerance about the band's middle).
    pub half: f64,
    /// Mean shift this dimension adds to Z: c_i·s_i·m_i.
    pub shift: f64,
    /// Share of the worst-case tolerance, percent: t_i / Σ t.
    pub pct_worst_case: f64,
    /// Share of the variance of Z, percent: σ_i² / Σ σ².
    pub pct_variance: f64,
}

/// Analytic stack-up of one dependent dimension.
#[derive(Debug, Clone, PartialEq)]
pub struct Stack {
    /// Nominal Z.
    pub nominal: f64,
    /// Mean Z after the mean shifts of asymmetric tolerances.
    pub mean: f64,
    /// Worst-case half-band Σ t_i.
    pub worst_case: f64,
    /// RSS half-band sqrt(Σ t_i²).
    pub rss: f64,
    /// Modified RSS half-band min(f·RSS, worst case).
    pub mrss: f64,
    /// Factor f of the modified RSS.
    pub mrss_factor: f64,
    /// Standard deviation of Z under the scene's distribution: sqrt(Σ σ_i²).
    pub sigma: f64,
    /// Per dimension, in the order of the function's terms.
    pub contributions: Vec<Contribution>,
}

/// Worst case, RSS, modified RSS and contributions of `f`.
pub fn stack(f: &Function, dims: &[Dimension], mrss_factor: f64, dist: Distribution) -> Stack {
    let mut mean = f.nominal;
    let mut wc = 0.0;
    let mut sq = 0.0;
    let mut var = 0.0;
    for t in &f.terms {
        let d = &dims[t.dim];
        mean += t.coef * d.sign() * d.mid();
        wc += d.half();
        sq += d.half() * d.half();
        let s = dist.sigma(d.half());
        var += s * s;
    }
    let rss = sq.sqrt();
    let contributions = f
        .terms
        .iter()
        .map(|t| {
            let d = &dims[t.dim];
            let h = d.half();
            Contribution {
                dim: t.dim,
                coef: t.coef,
                half: h,
                shift: t.coef * d.sign() * d.mid(),
                pct_worst_case: if wc > 0.0 { 100.0 * h / wc } else { 0.0 },
                pct_variance: if var > 0.0 { 100.0 * dist.sigma(h) * dist.sigma(h) / var } else { 0.0 },
            }
        })
        .collect();
    Stack {
        nominal: f.nominal,
        mean,
        worst_case: wc,
        rss,
        mrss: (mrss_factor * rss).min(wc),
        mrss_factor,
        sigma: var.sqrt(),
        contributions,
    }
}

/// Result of a Monte Carlo run on one dependent dimension.
#[derive(Debug, Clone, PartialEq)]
pub struct MonteCarlo {
    /// Sample count.
    pub samples: u64,
    /// Sample mean.
    pub mean: f64,
    /// Sample standard deviation (n − 1).
    pub sigma: f64,
    /// Smallest sample.
    pub min: f64,
    /// Largest sample.
    pub max: f64,
    /// `(percent, value)` for each of [`PERCENTILES`] (nearest rank).
    pub percentiles: Vec<(f64, f64)>,
    /// Histogram: left edge of the first bin, bin width, counts (over [min, max]).
    pub histogram: (f64, f64, Vec<u64>),
    /// With spec limits: the fraction of samples outside them, parts per million.
    pub out_of_spec_ppm: Option<f64>,
    /// With spec limits: the out-of-spec fraction of a normal distribution with the sample
    /// mean and σ, parts per million (resolves fractions far below 1/samples).
    pub out_of_spec_ppm_normal: Option<f64>,
    /// With spec limits: Cp = (USL − LSL) / 6σ (`None` when σ = 0).
    pub cp: Option<f64>,
    /// With spec limits: Cpk = min(USL − mean, mean − LSL) / 3σ (`None` when σ = 0).
    pub cpk: Option<f64>,
}

/// Mean of Z after the mean shifts, and the scale k_i·t_i of each term's symmetric
/// deviation in Z (terms without tolerance left out).
fn centre_and_scales(f: &Function, dims: &[Dimension]) -> (f64, Vec<f64>) {
    let mean: f64 = f.nominal + f.terms.iter().map(|t| t.coef * dims[t.dim].sign() * dims[t.dim].mid()).sum::<f64>();
    let scales: Vec<f64> =
        f.terms.iter().map(|t| t.coef * dims[t.dim].sign() * dims[t.dim].half()).filter(|s| *s != 0.0).collect();
    (mean, scales)
}

/// Fills `chunk` (chunk number `k` of a run, at most [`CHUNK`] long) with samples of Z:
/// random stream `k` of `seed`, so the values do not depend on which thread draws them.
fn draw_chunk(chunk: &mut [f64], k: usize, seed: u64, mean: f64, scales: &[f64], dist: Distribution) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(k as u64);
    for z in chunk.iter_mut() {
        let mut acc = 0.0;
        for s in scales {
            let e = match dist {
                Distribution::Normal => {
                    let n: f64 = StandardNormal.sample(&mut rng);
                    n / 3.0
                }
                Distribution::Uniform => 2.0 * rng.random::<f64>() - 1.0,
                Distribution::Triangular => rng.random::<f64>() + rng.random::<f64>() - 1.0,
            };
            acc += s * e;
        }
        *z = mean + acc;
    }
}

/// Draws `samples` values of Z (seeded, deterministic for any thread count).
pub fn sample(f: &Function, dims: &[Dimension], dist: Distribution, samples: usize, seed: u64) -> Vec<f64> {
    let (mean, scales) = centre_and_scales(f, dims);
    // Zeroed memory comes from the allocator untouched; each chunk is first written by the
    // thread that draws it (no serial fill pass).
    let mut out = vec![0.0; samples];
    out.par_chunks_mut(CHUNK).enumerate().for_each(|(k, chunk)| draw_chunk(chunk, k, seed, mean, &scales, dist));
    out
}

/// Bins of the fine histogram that locates the percentiles' ranks (pass 2 of
/// [`monte_carlo`]): 4096 counts (32 KiB) stay in a core's cache, and the bins holding the
/// five ranks keep about 4·n/4096 samples at most for a normal Z (the median's bin).
const RANK_BINS: usize = 4096;

/// Bin of `v` among `bins` bins of `width` from `x0`, the last bin closed. Monotone
/// non-decreasing in `v` (each step rounds monotonically), so every sample of a lower bin
/// is ≤ every sample of a higher one: ranks can be counted bin by bin.
fn bin_of(v: f64, x0: f64, width: f64, bins: usize) -> usize {
    (((v - x0) / width) as usize).min(bins - 1)
}

/// What pass 2 of [`monte_carlo`] counts over the samples.
struct Tally {
    /// `(chunk number, Σ (z − mean)² over the chunk)`, summed in chunk order at the end.
    squares: Vec<(usize, f64)>,
    /// Samples outside the spec limits.
    out_of_spec: u64,
    /// The reported histogram.
    histogram: Vec<u64>,
    /// The fine histogram of [`RANK_BINS`] bins over the same span.
    ranks: Vec<u64>,
}

impl Tally {
    fn new(bins: usize) -> Tally {
        Tally { squares: Vec::new(), out_of_spec: 0, histogram: vec![0; bins], ranks: vec![0; RANK_BINS] }
    }

    /// Counts are integers: adding them in any order gives the same totals.
    fn merge(mut self, other: Tally) -> Tally {
        self.squares.extend(other.squares);
        self.out_of_spec += other.out_of_spec;
        self.histogram.iter_mut().zip(other.histogram).for_each(|(a, b)| *a += b);
        self.ranks.iter_mut().zip(other.ranks).for_each(|(a, b)| *a += b);
        self
    }
}

/// Monte Carlo of `f`: statistics of [`sample`], histogram with `bins` bins, and with
/// `spec = [LSL, USL]` the out-of-spec fraction and Cp/Cpk. `None` when `samples` is 0.
///
/// Linear in `samples`: the samples are drawn chunk by chunk ([`CHUNK`]) and read in three
/// passes, each streaming through them once (the sum, min and max while each chunk is drawn;
/// the squares about the mean, both histograms and the out-of-spec count; the samples of
/// the few fine bins that hold the percentiles' ranks). Sums are taken per chunk and the
/// chunks' sums added in chunk order, so a seeded run gives the same last digit on any
/// thread count. The percentiles are exact order statistics (nearest rank): a fine
/// histogram finds the bin holding each rank and selection within that bin's samples finds
/// the value, with no sort.
pub fn monte_carlo(
    f: &Function,
    dims: &[Dimension],
    dist: Distribution,
    samples: u64,
    seed: u64,
    bins: u32,
    spec: Option<[f64; 2]>,
) -> Option<MonteCarlo> {
    if samples == 0 {
        return None;
    }
    let (centre, scales) = centre_and_scales(f, dims);
    let mut z = vec![0.0; samples as usize];
    let n = z.len() as f64;

    // Pass 1: draw each chunk and take its sum, min and max while it is in cache.
    let firsts: Vec<(f64, f64, f64)> = z
        .par_chunks_mut(CHUNK)
        .enumerate()
        .map(|(k, c)| {
            draw_chunk(c, k, seed, centre, &scales, dist);
            let (lo, hi) = c.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
            (c.iter().sum::<f64>(), lo, hi)
        })
        .collect();
    let mean = firsts.iter().map(|p| p.0).sum::<f64>() / n;
    let (min, max) =
        firsts.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &(_, lo, hi)| (a.min(lo), b.max(hi)));
    let bins = bins.max(1) as usize;
    let span = if max > min { max - min } else { (mean.abs() * 1e-9).max(1e-12) };
    let x0 = if max > min { min } else { mean - span / 2.0 };
    let width = span / bins as f64;
    let rank_width = span / RANK_BINS as f64;

    // Pass 2: squares about the mean per chunk, the histograms and the out-of-spec count.
    let mut tally = z
        .par_chunks(CHUNK)
        .enumerate()
        .fold(
            || Tally::new(bins),
            |mut t, (k, c)| {
                t.squares.push((k, c.iter().map(|&v| (v - mean) * (v - mean)).sum::<f64>()));
                for &v in c {
                    t.histogram[bin_of(v, x0, width, bins)] += 1;
                    t.ranks[bin_of(v, x0, rank_width, RANK_BINS)] += 1;
                }
                if let Some([lsl, usl]) = spec {
                    t.out_of_spec += c.iter().filter(|v| **v < lsl || **v > usl).count() as u64;
                }
                t
            },
        )
        .reduce(|| Tally::new(bins), Tally::merge);
    tally.squares.sort_by_key(|p| p.0);
    let ss = tally.squares.iter().map(|p| p.1).sum::<f64>();
    let sigma = if z.len() > 1 { (ss / (n - 1.0)).sqrt() } else { 0.0 };

    let (out_of_spec_ppm, cp, cpk) = match spec {
        Some([lsl, usl]) => {
            let (cp, cpk) = if sigma > 0.0 {
                (Some((usl - lsl) / (6.0 * sigma)), Some((usl - mean).min(mean - lsl) / (3.0 * sigma)))
            } else {
                (None, None)
            };
            (Some(1e6 * tally.out_of_spec as f64 / n), cp, cpk)
        }
        None => (None, None, None),
    };
    let out_of_spec_ppm_normal = spec.filter(|_| sigma > 0.0).map(|[lsl, usl]| {
        let tail = |d: f64| 0.5 * erfc(d / (sigma * std::f64::consts::SQRT_2));
        1e6 * (tail(usl - mean) + tail(mean - lsl))
    });

    // Pass 3: nearest-rank percentiles. Each rank falls in one fine bin (its rank among
    // the samples of that bin = its rank less the samples of the bins below); the samples
    // of those bins are gathered and the value picked by selection.
    let below: Vec<u64> = tally
        .ranks
        .iter()
        .scan(0u64, |acc, &c| {
            let b = *acc;
            *acc += c;
            Some(b)
        })
        .collect();
    let located: Vec<(f64, usize, usize)> = PERCENTILES
        .iter()
        .map(|&p| {
            let rank = (((p / 100.0) * (n - 1.0)).round() as usize).min(z.len() - 1) as u64;
            // The last bin whose first rank is ≤ rank (empty bins share their first rank).
            let bin = below.partition_point(|&b| b <= rank) - 1;
            (p, bin, (rank - below[bin]) as usize)
        })
        .collect();
    let mut wanted: Vec<usize> = located.iter().map(|l| l.1).collect();
    wanted.sort_unstable();
    wanted.dedup();
    let mut gathered = z
        .par_chunks(CHUNK)
        .fold(
            || vec![Vec::new(); wanted.len()],
            |mut g: Vec<Vec<f64>>, c| {
                for &v in c {
                    if let Ok(i) = wanted.binary_search(&bin_of(v, x0, rank_width, RANK_BINS)) {
                        g[i].push(v);
                    }
                }
                g
            },
        )
        .reduce(
            || vec![Vec::new(); wanted.len()],
            |mut a, b| {
                a.iter_mut().zip(b).for_each(|(x, y)| x.extend(y));
                a
            },
        );
    drop(z);
    let percentiles = located
        .iter()
        .map(|&(p, bin, offset)| {
            let i = wanted.binary_search(&bin).expect("a located bin is gathered");
            let (_, v, _) = gathered[i].select_nth_unstable_by(offset, f64::total_cmp);
            (p, *v)
        })
        .collect();
    Some(MonteCarlo {
        samples,
        mean,
        sigma,
        min,
        max,
        percentiles,
        histogram: (x0, width, tally.histogram),
        out_of_spec_ppm,
        out_of_spec_ppm_normal,
        cp,
        cpk,
    })
}

/// The complementary error function, fractional error below 1.2e-7 everywhere
/// (Chebyshev fit of Numerical Recipes, 2nd ed., §6.2 `erfcc`).
pub fn erfc(x: f64) -> f64 {
    let z = x.abs();
    let t = 1.0 / (1.0 + 0.5 * z);
    let poly = -z * z - 1.265_512_23
        + t * (1.000_023_68
            + t * (0.374_091_96
                + t * (0.096_784_18
                    + t * (-0.186_288_06
                        + t * (0.278_868_07
                            + t * (-1.135_203_98 + t * (1.488_515_87 + t * (-0.822_152_23 + t * 0.170_872_77))))))));
    let r = t * libm::exp(poly);
    if x >= 0.0 { r } else { 2.0 - r }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::chain::Term;

    fn d(nominal: f64, upper: f64, lower: f64) -> Dimension {
        Dimension { name: "w".into(), from: 0, to: 1, nominal, upper, lower }
    }

    #[test]
    fn an_asymmetric_band_is_a_mean_shift_with_the_sign_of_the_dimension() {
        // Z = -w1 + w2, w1 = -38 (+0.1/-0.05 on its size 38), w2 = 80 ±0.1.
        // Size of w1 ∈ [37.95, 38.1] → w1 ∈ [-38.1, -37.95], mid -38.025 → -w1 mid 38.025.
        let dims = vec![d(-38.0, 0.1, -0.05), d(80.0, 0.1, -0.1)];
        let f = Function { terms: vec![Term { dim: 0, coef: -1.0 }, Term { dim: 1, coef: 1.0 }], nominal: 118.0 };
        let s = stack(&f, &dims, 1.5, Distribution::Normal);
        assert!((s.mean - 118.025).abs() < 1e-12);
        assert!((s.worst_case - 0.175).abs() < 1e-12);
        // Extremes by enumeration of the band ends.
        let zs: Vec<f64> = [37.95, 38.1].iter().flat_map(|a| [79.9, 80.1].map(|b| a + b)).collect();
        let zmax = zs.iter().cloned().fold(f64::MIN, f64::max);
        let zmin = zs.iter().cloned().fold(f64::MAX, f64::min);
        assert!((s.mean + s.worst_case - zmax).abs() < 1e-12);
        assert!((s.mean - s.worst_case - zmin).abs() < 1e-12);
    }

    #[test]
    fn sampling_is_deterministic_and_independent_of_the_chunking_threads() {
        let dims = vec![d(10.0, 0.1, -0.1), d(20.0, 0.2, -0.2)];
        let f = Function { terms: vec![Term { dim: 0, coef: 1.0 }, Term { dim: 1, coef: 1.0 }], nominal: 30.0 };
        let a = sample(&f, &dims, Distribution::Uniform, 3 * CHUNK + 7, 42);
        let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
        let b = pool.install(|| sample(&f, &dims, Distribution::Uniform, 3 * CHUNK + 7, 42));
        assert_eq!(a, b);
        assert!(a.iter().all(|z| (z - 30.0).abs() <= 0.3));
    }

    #[test]
    fn monte_carlo_statistics_do_not_depend_on_the_thread_count() {
        let dims = vec![d(10.0, 0.1, -0.1), d(20.0, 0.2, -0.2), d(5.0, 0.05, -0.02)];
        let terms = vec![Term { dim: 0, coef: 1.0 }, Term { dim: 1, coef: -1.0 }, Term { dim: 2, coef: 1.0 }];
        let f = Function { terms, nominal: -5.0 };
        let run = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| monte_carlo(&f, &dims, Distribution::Normal, 50 * CHUNK as u64 + 13, 7, 40, None).unwrap())
        };
        let one = run(1);
        for threads in [2, 3, 5] {
            let other = run(threads);
            // Bit for bit: a seeded run is reproducible to the last digit.
            assert_eq!(one.mean.to_bits(), other.mean.to_bits(), "mean with {threads} threads");
            assert_eq!(one.sigma.to_bits(), other.sigma.to_bits(), "sigma with {threads} threads");
            assert_eq!(one.histogram, other.histogram);
            assert_eq!(one.percentiles, other.percentiles);
        }
    }

    /// The old route, written out independently: the whole sample, sums per chunk added in
    /// chunk order, a full sort for the nearest-rank percentiles, counts by direct loops.
    fn by_sorting(z: &[f64], bins: usize, spec: Option<[f64; 2]>) -> MonteCarlo {
        let n = z.len() as f64;
        let sum_by_chunk = |g: &dyn Fn(f64) -> f64| -> f64 {
            let partial: Vec<f64> = z.chunks(CHUNK).map(|c| c.iter().map(|&v| g(v)).sum::<f64>()).collect();
            partial.iter().sum()
        };
        let mean = sum_by_chunk(&|v| v) / n;
        let sigma = if z.len() > 1 { (sum_by_chunk(&|v| (v - mean) * (v - mean)) / (n - 1.0)).sqrt() } else { 0.0 };
        let mut sorted = z.to_vec();
        sorted.sort_by(f64::total_cmp);
        let (min, max) = (sorted[0], sorted[z.len() - 1]);
        let span = if max > min { max - min } else { (mean.abs() * 1e-9).max(1e-12) };
        let x0 = if max > min { min } else { mean - span / 2.0 };
        let width = span / bins as f64;
        let mut counts = vec![0u64; bins];
        for v in z {
            counts[(((v - x0) / width) as usize).min(bins - 1)] += 1;
        }
        let percentiles =
            PERCENTILES.iter().map(|&p| (p, sorted[((p / 100.0) * (n - 1.0)).round() as usize])).collect();
        let out = spec.map(|[lsl, usl]| 1e6 * z.iter().filter(|v| **v < lsl || **v > usl).count() as f64 / n);
        MonteCarlo {
            samples: z.len() as u64,
            mean,
            sigma,
            min,
            max,
            percentiles,
            histogram: (x0, width, counts),
            out_of_spec_ppm: out,
            out_of_spec_ppm_normal: None,
            cp: None,
            cpk: None,
        }
    }

    #[test]
    fn streaming_statistics_and_selected_percentiles_equal_the_sorted_whole_sample() {
        let dims = vec![d(10.0, 0.1, -0.1), d(-20.0, 0.2, -0.05), d(5.0, 0.05, -0.02), d(7.0, 0.0, 0.0)];
        let terms = vec![
            Term { dim: 0, coef: 1.0 },
            Term { dim: 1, coef: -1.0 },
            Term { dim: 2, coef: 1.0 },
            Term { dim: 3, coef: 1.0 },
        ];
        let f = Function { terms, nominal: 42.0 };
        let spec = Some([41.9, 42.2]);
        for (dist, samples, bins) in [
            (Distribution::Normal, 1, 40),
            (Distribution::Normal, 2, 40),
            (Distribution::Uniform, 7, 3),
            (Distribution::Triangular, CHUNK + 1, 40),
            (Distribution::Normal, 5 * CHUNK + 3, 40),
            (Distribution::Uniform, 300_001, 17),
            (Distribution::Normal, 1_000_000, 40),
        ] {
            let mc = monte_carlo(&f, &dims, dist, samples as u64, 11, bins, spec).unwrap();
            let old = by_sorting(&sample(&f, &dims, dist, samples, 11), bins as usize, spec);
            let what = format!("{dist:?}, {samples} samples");
            assert_eq!(mc.mean.to_bits(), old.mean.to_bits(), "mean, {what}");
            assert_eq!(mc.sigma.to_bits(), old.sigma.to_bits(), "sigma, {what}");
            assert_eq!((mc.min, mc.max), (old.min, old.max), "{what}");
            assert_eq!(mc.histogram, old.histogram, "{what}");
            assert_eq!(mc.out_of_spec_ppm, old.out_of_spec_ppm, "{what}");
            // Exact order statistics, bit for bit.
            for ((p, v), (_, w)) in mc.percentiles.iter().zip(&old.percentiles) {
                assert_eq!(v.to_bits(), w.to_bits(), "{p} % percentile, {what}: {v} vs {w}");
            }
        }
    }

    #[test]
    fn a_chain_without_tolerance_gives_its_mean_at_every_percentile() {
        let dims = vec![d(10.0, 0.0, 0.0), d(20.0, 0.0, 0.0)];
        let f = Function { terms: vec![Term { dim: 0, coef: 1.0 }, Term { dim: 1, coef: 1.0 }], nominal: 30.0 };
        let mc = monte_carlo(&f, &dims, Distribution::Normal, 1000, 1, 10, None).unwrap();
        assert_eq!((mc.mean, mc.sigma, mc.min, mc.max), (30.0, 0.0, 30.0, 30.0));
        assert!(mc.percentiles.iter().all(|(_, v)| *v == 30.0));
        assert_eq!(mc.histogram.2.iter().sum::<u64>(), 1000);
    }

    #[test]
    fn erfc_matches_tabulated_values() {
        // Abramowitz & Stegun table 7.1 / exact: erfc(0) = 1, erfc(1) = 0.157299207,
        // erfc(3/√2) = 0.002699796 (the two-sided 3σ tail), erfc(-1) = 1.842700793.
        for (x, v) in [(0.0, 1.0), (1.0, 0.157_299_207), (3.0 / 2f64.sqrt(), 0.002_699_796), (-1.0, 1.842_700_793)] {
            assert!((erfc(x) - v).abs() <= 2e-7 * v, "erfc({x}) = {} vs {v}", erfc(x));
        }
    }
}
