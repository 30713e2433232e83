//! The Monte Carlo over the whole motion: each sample a new mechanism (every toleranced
//! dimension drawn from its distribution), solved at every position by the model, each
//! component's deviation streamed into per-position statistics ([`Tally`]), the samples that
//! cannot be assembled counted and located.
//!
//! Reproducible on any number of threads and in shards: the samples come in chunks of
//! [`CHUNK`], chunk k drawn from random stream k of the seed (ChaCha8, as the chain's
//! stack-up draws), each sample's dimensions in their order; a chunk's sums are taken in
//! its sample order and then added exactly, and counts and extremes do not depend on order.
//! A shard K/N runs a contiguous share of the chunks ([`shard_chunks`]); its tallies merge
//! into the single run's bit for bit.

use std::ops::Range;

use crate::par::prelude::*;
use rand::distr::Distribution as _;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;

use super::model::{Component, Dimension, Distribution};
use super::stats::Tally;

/// Samples drawn from one random stream.
pub const CHUNK: u64 = 256;
/// Most samples one study draws (over all its shards): 2^32, so that chunk numbers fit a
/// `usize` on every target.
pub const MAX_SAMPLES: u64 = 1 << 32;

/// A mechanism watched over its positions as a function of its toleranced dimensions.
pub trait Model: Sync {
    /// Per-thread buffers (a solver, its scratch).
    type Work: Send;
    /// Positions watched (the nominal's solved ones).
    fn positions(&self) -> usize;
    /// Channels per position (a point's x and y deviations, an angle's deviation).
    fn channels(&self) -> usize;
    /// A fresh set of buffers.
    fn work(&self) -> Self::Work;
    /// The channels' deviations from nominal at every position (position-major, into
    /// `out`, `positions() · channels()` values) for the dimensions deviated by `dev` (one per
    /// dimension, in its unit). A position where this mechanism cannot be assembled is set
    /// in `failed` (its channels are then left as they are); returns whether any is.
    fn evaluate(&self, work: &mut Self::Work, dev: &[f64], out: &mut [f64], failed: &mut [bool]) -> bool;
}

/// Number of chunks of `samples`.
pub fn chunk_count(samples: u64) -> u64 {
    samples.div_ceil(CHUNK)
}

/// The chunks shard `index` of `count` (1-based) runs: a contiguous share, the shards
/// together every chunk once.
pub fn shard_chunks(samples: u64, index: u64, count: u64) -> Range<u64> {
    let c = chunk_count(samples) as u128;
    let (i, n) = (index.max(1) as u128, count.max(1) as u128);
    ((c * (i - 1) / n) as u64)..((c * i / n) as u64)
}

/// One sample's deviations into `dev`, drawn from `rng` in the dimensions' order.
pub fn draw(dims: &[Dimension], rng: &mut ChaCha8Rng, dev: &mut [f64]) {
    for (d, out) in dims.iter().zip(dev.iter_mut()) {
        let e = match d.distribution {
            Distribution::Normal { k } => {
                let z: f64 = StandardNormal.sample(rng);
                z / k
            }
            Distribution::Uniform => 2.0 * rng.random::<f64>() - 1.0,
            Distribution::Triangular => rng.random::<f64>() + rng.random::<f64>() - 1.0,
        };
        *out = d.mid() + d.half() * e;
    }
}

/// The random stream of chunk `k`.
fn stream(seed: u64, k: u64) -> ChaCha8Rng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(k);
    rng
}

/// Sample `j`'s deviations (replaying its chunk's stream up to it): what the run drew.
pub fn sample_deviations(dims: &[Dimension], seed: u64, j: u64) -> Vec<f64> {
    let mut rng = stream(seed, j / CHUNK);
    let mut dev = vec![0.0; dims.len()];
    for _ in 0..=j % CHUNK {
        draw(dims, &mut rng, &mut dev);
    }
    dev
}

/// What a run (or a shard) of the Monte Carlo counted.
#[derive(Debug, Clone, PartialEq)]
pub struct MonteCarlo {
    /// Samples drawn.
    pub drawn: u64,
    /// Samples that could not be assembled at some position (left out of the tallies).
    pub failed_samples: u64,
    /// Per position, the samples that could not be assembled there.
    pub failed_at: Vec<u64>,
    /// Per position and component (position-major), the assembled samples' deviations.
    pub tallies: Vec<Tally>,
}

impl MonteCarlo {
    /// Adds another run's counts (a shard's): exact.
    pub fn merge(&mut self, o: &MonteCarlo) {
        self.drawn += o.drawn;
        self.failed_samples += o.failed_samples;
        for (a, b) in self.failed_at.iter_mut().zip(&o.failed_at) {
            *a += b;
        }
        for (a, b) in self.tallies.iter_mut().zip(&o.tallies) {
            a.merge(b);
        }
    }
}

/// A thread's accumulator and buffers.
struct Acc<W> {
    mc: MonteCarlo,
    sums: Vec<f64>,
    squares: Vec<f64>,
    work: W,
    dev: Vec<f64>,
    out: Vec<f64>,
    failed: Vec<bool>,
}

/// Runs chunks `chunks` of a Monte Carlo of `samples` samples with `seed`: every sample's
/// components (`comps`) at every position counted into a tally over its range (`ranges`,
/// position-major like the tallies, `bins` bins each).
#[allow(clippy::too_many_arguments)]
pub fn run<M: Model>(
    model: &M,
    dims: &[Dimension],
    comps: &[Component],
    ranges: &[(f64, f64)],
    bins: usize,
    samples: u64,
    seed: u64,
    chunks: Range<u64>,
) -> MonteCarlo {
    let (np, nc, ch) = (model.positions(), comps.len(), model.channels());
    let empty = || MonteCarlo {
        drawn: 0,
        failed_samples: 0,
        failed_at: vec![0; np],
        tallies: ranges.iter().map(|&(lo, hi)| Tally::new(lo, hi, bins)).collect(),
    };
    let new_acc = || Acc {
        mc: empty(),
        sums: vec![0.0; np * nc],
        squares: vec![0.0; np * nc],
        work: model.work(),
        dev: vec![0.0; dims.len()],
        out: vec![0.0; np * ch],
        failed: vec![false; np],
    };
    // Chunk numbers fit a usize: a run has at most MAX_SAMPLES / CHUNK of them.
    let accs: Vec<MonteCarlo> = (chunks.start as usize..chunks.end as usize)
        .into_par_iter()
        .with_min_len(2)
        .fold(new_acc, |mut acc, k| {
            chunk(model, dims, comps, &mut acc, samples, seed, k as u64);
            acc
        })
        .map(|a| a.mc)
        .collect();
    let mut total = empty();
    for a in &accs {
        total.merge(a);
    }
    total
}

/// One chunk into `acc`.
fn chunk<M: Model>(
    model: &M,
    dims: &[Dimension],
    comps: &[Component],
    acc: &mut Acc<M::Work>,
    samples: u64,
    seed: u64,
    k: u64,
) {
    let (np, nc, ch) = (model.positions(), comps.len(), model.channels());
    let mut rng = stream(seed, k);
    let first = k * CHUNK;
    let last = (first + CHUNK).min(samples);
    acc.sums.iter_mut().chain(acc.squares.iter_mut()).for_each(|v| *v = 0.0);
    for _ in first..last {
        draw(dims, &mut rng, &mut acc.dev);
        acc.mc.drawn += 1;
        acc.failed.iter_mut().for_each(|f| *f = false);
        let mut bad = model.evaluate(&mut acc.work, &acc.dev, &mut acc.out, &mut acc.failed);
        for p in 0..np {
            if !acc.failed[p] && acc.out[p * ch..(p + 1) * ch].iter().any(|v| !v.is_finite()) {
                acc.failed[p] = true;
                bad = true;
            }
        }
        if bad {
            acc.mc.failed_samples += 1;
            for (n, f) in acc.mc.failed_at.iter_mut().zip(&acc.failed) {
                *n += u64::from(*f);
            }
            continue;
        }
        for p in 0..np {
            let channels = &acc.out[p * ch..(p + 1) * ch];
            for (c, comp) in comps.iter().enumerate() {
                let v = comp.projection.of(p, channels);
                let i = p * nc + c;
                acc.sums[i] += v;
                acc.squares[i] += v * v;
                acc.mc.tallies[i].count(v);
            }
        }
    }
    for ((t, s), q) in acc.mc.tallies.iter_mut().zip(&acc.sums).zip(&acc.squares) {
        t.add_sums(*s, *q);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::tolerance::model::Projection;

    /// y = a + b at one position, z = a·b at another (channel 0).
    struct Toy;
    impl Model for Toy {
        type Work = ();
        fn positions(&self) -> usize {
            2
        }
        fn channels(&self) -> usize {
            1
        }
        fn work(&self) {}
        fn evaluate(&self, _: &mut (), dev: &[f64], out: &mut [f64], failed: &mut [bool]) -> bool {
            out[0] = dev[0] + dev[1];
            out[1] = (1.0 + dev[0]) * (1.0 + dev[1]) - 1.0;
            // "Cannot assemble" the second position when both are high.
            failed[1] = dev[0] > 0.5 && dev[1] > 0.3;
            failed[1]
        }
    }

    fn dims() -> Vec<Dimension> {
        let d = |distribution| Dimension { name: "d".into(), nominal: 0.0, upper: 1.0, lower: -1.0, distribution };
        vec![d(Distribution::Uniform), d(Distribution::Normal { k: 3.0 })]
    }

    fn comps() -> Vec<Component> {
        vec![Component {
            name: "v.value".into(),
            output: "v".into(),
            part: "value",
            absolute: true,
            projection: Projection::Channel(0),
        }]
    }

    #[test]
    fn shards_merge_into_the_single_run_bit_for_bit_on_any_thread_count() {
        let (dims, comps) = (dims(), comps());
        let ranges = vec![(-2.0, 2.0), (-2.0, 2.0)];
        let samples = 10 * CHUNK + 17;
        let whole = run(&Toy, &dims, &comps, &ranges, 50, samples, 9, 0..chunk_count(samples));
        let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
        let one = pool.install(|| run(&Toy, &dims, &comps, &ranges, 50, samples, 9, 0..chunk_count(samples)));
        assert_eq!(whole, one);
        let mut merged: Option<MonteCarlo> = None;
        for k in (1..=4).rev() {
            let s = run(&Toy, &dims, &comps, &ranges, 50, samples, 9, shard_chunks(samples, k, 4));
            match &mut merged {
                None => merged = Some(s),
                Some(m) => m.merge(&s),
            }
        }
        let merged = merged.unwrap();
        assert_eq!(merged, whole);
        assert_eq!(whole.drawn, samples);
        let (a, b) = (whole.tallies[0].summary().unwrap(), merged.tallies[0].summary().unwrap());
        assert_eq!(a.sigma.to_bits(), b.sigma.to_bits());
        assert_eq!(a.p_high.to_bits(), b.p_high.to_bits());
        // Failures are counted where they happen, and only there.
        assert!(whole.failed_samples > 0);
        assert_eq!(whole.failed_at[0], 0);
        assert_eq!(whole.failed_at[1], whole.failed_samples);
        assert_eq!(whole.tallies[0].n + whole.failed_samples, samples);
    }

    #[test]
    fn a_sample_replays_from_its_chunk_stream() {
        let dims = dims();
        let j = 3 * CHUNK + 5;
        let mut rng = stream(4, 3);
        let mut dev = vec![0.0; 2];
        for _ in 0..6 {
            draw(&dims, &mut rng, &mut dev);
        }
        assert_eq!(sample_deviations(&dims, 4, j), dev);
        assert!(dev[0].abs() <= 1.0);
    }
}
