//! Tolerance stack-up against closed forms: worst case Σ|t_i|, RSS sqrt(Σ t_i²), the
//! standard deviation of a sum of independent normal / uniform / triangular deviations,
//! the normal distribution's ±3σ fraction, the mean shift of asymmetric tolerances.

mod common;

use mechdraw::scene::{self, Override, Scene};
use mechdraw::solve::chain::{Chain, Distribution, analyse, monte_carlo, stack};

const TOLS: [f64; 8] = [0.01, 0.02, 0.03, 0.04, 0.05, 0.06, 0.07, 0.08];

fn seed_2_with_tolerances(extra: &[&str]) -> Chain {
    let text = std::fs::read_to_string(common::root().join("templates/chain-humienny-2.toml")).unwrap();
    let mut sets: Vec<Override> = vec!["tol=[0.01, 0.02, 0.03, 0.04, 0.05, 0.06, 0.07, 0.08]".parse().unwrap()];
    sets.extend(extra.iter().map(|s| s.parse::<Override>().unwrap()));
    match scene::parse(&text, "t.toml", &sets).unwrap() {
        Scene::Chain(c) => c.chain,
        _ => unreachable!(),
    }
}

#[test]
fn worst_case_and_rss_sum_the_tolerances_along_the_path() {
    let s = seed_2_with_tolerances(&[]);
    let a = analyse(&s);
    // Paths (see chain_seed.rs): Z1 = w1 - w2 + w3, Z2 = w1 + w3, Z3 = w4 + w5 + w6,
    // Z4 = -w3 + w4 + w5.
    let paths: [&[usize]; 4] = [&[0, 1, 2], &[0, 2], &[3, 4, 5], &[2, 3, 4]];
    for (z, path) in s.dependent.iter().zip(paths) {
        let f = a.function(&s, z).unwrap();
        let st = stack(&f, &s.dimensions, 1.5, Distribution::Normal);
        let wc: f64 = path.iter().map(|&i| TOLS[i]).sum();
        let rss: f64 = path.iter().map(|&i| TOLS[i] * TOLS[i]).sum::<f64>().sqrt();
        assert!(common::rel_close(st.worst_case, wc, 1e-14, 1e-12), "{}: {} vs {wc}", z.name, st.worst_case);
        assert!(common::rel_close(st.rss, rss, 1e-14, 1e-12), "{}: {} vs {rss}", z.name, st.rss);
        assert!(common::rel_close(st.mrss, (1.5 * rss).min(wc), 1e-14, 1e-12));
        assert_eq!(st.mean, st.nominal); // symmetric tolerances: no shift
        // Contributions: t_i / Σ t and t_i² / Σ t².
        for c in &st.contributions {
            let t = TOLS[c.dim];
            assert!(common::rel_close(c.pct_worst_case, 100.0 * t / wc, 1e-12, 1e-12));
            assert!(common::rel_close(c.pct_variance, 100.0 * t * t / (rss * rss), 1e-12, 1e-12));
        }
        let total: f64 = st.contributions.iter().map(|c| c.pct_variance).sum();
        assert!((total - 100.0).abs() < 1e-9);
    }
}

#[test]
fn monte_carlo_sigma_is_within_one_percent_of_the_closed_form() {
    let s = seed_2_with_tolerances(&[]);
    let a = analyse(&s);
    let z = &s.dependent[2]; // Z3 = w4 + w5 + w6, t = 0.04, 0.05, 0.06
    let f = a.function(&s, z).unwrap();
    let sum_t2: f64 = [0.04f64, 0.05, 0.06].iter().map(|t| t * t).sum();
    // σ of a sum of independent deviations: normal t/3, uniform t/√3, triangular t/√6.
    for (dist, sigma) in [
        (Distribution::Normal, (sum_t2 / 9.0).sqrt()),
        (Distribution::Uniform, (sum_t2 / 3.0).sqrt()),
        (Distribution::Triangular, (sum_t2 / 6.0).sqrt()),
    ] {
        let mc = monte_carlo(&f, &s.dimensions, dist, 200_000, 7, 40, None).unwrap();
        assert!(common::rel_close(mc.sigma, sigma, 0.01, 0.0), "{dist:?}: MC σ {} vs {sigma}", mc.sigma);
        assert!((mc.mean - 215.0).abs() < 0.01 * sigma * 10.0, "{dist:?}: mean {}", mc.mean);
        let st = stack(&f, &s.dimensions, 1.5, dist);
        assert!(common::rel_close(st.sigma, sigma, 1e-12, 0.0));
        if dist != Distribution::Normal {
            // Bounded distributions never leave the worst-case band.
            assert!(mc.min >= 215.0 - 0.15 - 1e-9 && mc.max <= 215.0 + 0.15 + 1e-9);
        }
        let total: u64 = mc.histogram.2.iter().sum();
        assert_eq!(total, 200_000);
    }
}

#[test]
fn spec_limits_at_three_sigma_give_2700_ppm_and_cp_one() {
    // Normal: P(|Z − μ| > 3σ) = erfc(3/√2) = 0.0026998 → 2699.8 ppm; Cp = Cpk = 1.
    let s = seed_2_with_tolerances(&[]);
    let a = analyse(&s);
    let z = &s.dependent[2];
    let f = a.function(&s, z).unwrap();
    let sigma = ([0.04f64, 0.05, 0.06].iter().map(|t| t * t).sum::<f64>() / 9.0).sqrt();
    let spec = [215.0 - 3.0 * sigma, 215.0 + 3.0 * sigma];
    let mc = monte_carlo(&f, &s.dimensions, Distribution::Normal, 400_000, 3, 40, Some(spec)).unwrap();
    let ppm = mc.out_of_spec_ppm.unwrap();
    // 1080 expected outside of 400000: binomial σ ≈ 33 → 3 %; allow 10 %.
    assert!(common::rel_close(ppm, 2699.8, 0.10, 0.0), "ppm {ppm}");
    // The normal model with the sample mean and σ: within the sampling error of μ and σ.
    let ppm_normal = mc.out_of_spec_ppm_normal.unwrap();
    assert!(common::rel_close(ppm_normal, 2699.8, 0.05, 0.0), "normal-model ppm {ppm_normal}");
    assert!(common::rel_close(mc.cp.unwrap(), 1.0, 0.01, 0.0), "Cp {:?}", mc.cp);
    assert!(common::rel_close(mc.cpk.unwrap(), 1.0, 0.02, 0.0), "Cpk {:?}", mc.cpk);
    // The ±3σ percentiles sit at μ ± 3σ (to the sampling error of a tail quantile).
    let p = |q: f64| mc.percentiles.iter().find(|(x, _)| *x == q).unwrap().1;
    assert!((p(0.135) - spec[0]).abs() < 0.05 * 3.0 * sigma);
    assert!((p(99.865) - spec[1]).abs() < 0.05 * 3.0 * sigma);
    assert!((p(50.0) - 215.0).abs() < 0.02 * sigma);
}

#[test]
fn an_asymmetric_tolerance_shifts_the_mean_of_the_monte_carlo_too() {
    // A —10 (+0.2/0)→ B —20 ±0.1→ C; Z = [A, C] = 30, mean 30.1, worst case ±0.2.
    let text = r#"
kind = "chain"
name = "asym"
units = "mm"
features = ["A", "B", "C"]
dependent = [["A", "C"]]
[[dimension]]
from = "A"
to = "B"
nominal = 10
upper = 0.2
lower = 0.0
[[dimension]]
from = "B"
to = "C"
nominal = 20
tol = 0.1
[stackup]
distribution = "uniform"
samples = 200000
"#;
    let s = match scene::parse(text, "t.toml", &[]).unwrap() {
        Scene::Chain(c) => c.chain,
        _ => unreachable!(),
    };
    let a = analyse(&s);
    let f = a.function(&s, &s.dependent[0]).unwrap();
    let st = stack(&f, &s.dimensions, 1.5, Distribution::Uniform);
    assert!((st.mean - 30.1).abs() < 1e-12);
    assert!((st.worst_case - 0.2).abs() < 1e-12);
    let mc = monte_carlo(&f, &s.dimensions, Distribution::Uniform, 200_000, 1, 20, None).unwrap();
    // Extremes of the real sizes: [10, 10.2] + [19.9, 20.1] = [29.9, 30.3].
    assert!(mc.min >= 29.9 - 1e-12 && mc.max <= 30.3 + 1e-12);
    let sigma = ((0.1f64 * 0.1 + 0.1 * 0.1) / 3.0).sqrt();
    assert!((mc.mean - 30.1).abs() < 5.0 * sigma / (200_000f64).sqrt());
}
