//! Dimensional chains: the check plus every dependent function on a chain of 1,000
//! dimensions (target ≤ 10 ms), a Monte Carlo of 1e6 samples (target ≤ 200 ms), and the
//! same Monte Carlo at 1e6 and 1e7 samples side by side (target: 1e7 within 12× of 1e6,
//! i.e. linear in the samples; issue 16 §5).
//!
//! Two shapes of chain: a random tree (each dimension based on a random earlier feature,
//! short paths, like a drawing dimensioned from several bases) and a serial chain (each
//! dimension based on the previous one, paths up to 1,000 dimensions long: the worst case).

use criterion::{Criterion, criterion_group, criterion_main};
use mechdraw::solve::chain::{Chain, Dependent, Dimension, Distribution, Form, analyse, monte_carlo};

/// A deterministic generator (splitmix64) so the bench needs no seed file.
struct Mix(u64);
impl Mix {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

fn chain(n: usize, serial: bool, dependents: usize) -> Chain {
    let mut rng = Mix(12345);
    let dimensions = (0..n)
        .map(|i| {
            let from = if serial { i } else { rng.below(i + 1) };
            let size = 1.0 + rng.below(1000) as f64 / 10.0;
            let nominal = if rng.below(4) == 0 { -size } else { size };
            Dimension { name: format!("w{}", i + 1), from, to: i + 1, nominal, upper: 0.05, lower: -0.05 }
        })
        .collect();
    let dependent = (0..dependents)
        .map(|k| Dependent {
            name: format!("Z{}", k + 1),
            left: rng.below(n + 1),
            right: rng.below(n + 1),
            label: String::new(),
            spec: None,
        })
        .collect();
    Chain { form: Form::Named, features: (0..=n).map(|i| format!("F{i}")).collect(), dimensions, dependent }
}

fn check_and_functions(s: &Chain) -> usize {
    let a = analyse(s);
    s.dependent.iter().map(|z| a.function(s, z).map_or(0, |f| f.terms.len())).sum()
}

fn bench(c: &mut Criterion) {
    let tree = chain(1000, false, 1000);
    let serial = chain(1000, true, 1000);
    c.bench_function("chain/check+1000 functions, 1000 dims, random tree", |b| b.iter(|| check_and_functions(&tree)));
    c.bench_function("chain/check+1000 functions, 1000 dims, serial chain", |b| {
        b.iter(|| check_and_functions(&serial))
    });
    // Monte Carlo: a 3-dimension path (like the template's Z3) and a 100-dimension path
    // of the serial chain.
    let short = chain(3, true, 0);
    let z_short = Dependent { name: "Z".into(), left: 0, right: 3, label: String::new(), spec: None };
    let f3 = analyse(&short).function(&short, &z_short).expect("tied");
    let z_long = Dependent { name: "Z".into(), left: 100, right: 200, label: String::new(), spec: Some([0.0, 1.0]) };
    let long = analyse(&serial).function(&serial, &z_long).expect("tied");
    assert_eq!(long.terms.len(), 100);
    let mut g = c.benchmark_group("chain/monte carlo 1e6");
    g.sample_size(10);
    for dist in [Distribution::Normal, Distribution::Uniform] {
        g.bench_function(format!("3 dims, {}", dist.name()), |b| {
            b.iter(|| monte_carlo(&f3, &short.dimensions, dist, 1_000_000, 1, 40, None))
        });
    }
    g.bench_function("100 dims, normal", |b| {
        b.iter(|| monte_carlo(&long, &serial.dimensions, Distribution::Normal, 1_000_000, 1, 40, Some([0.0, 1.0])))
    });
    g.finish();
    // Linear in the samples: the 3-dimension path at 1e6 and 1e7 (compare the two means).
    let mut g = c.benchmark_group("chain/monte carlo 1e6 vs 1e7");
    g.sample_size(10);
    for samples in [1_000_000u64, 10_000_000] {
        g.bench_function(format!("3 dims, normal, {samples} samples"), |b| {
            b.iter(|| monte_carlo(&f3, &short.dimensions, Distribution::Normal, samples, 1, 40, Some([0.0, 1.0])))
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
