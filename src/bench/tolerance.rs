//! The tolerance study's Monte Carlo timed (issue 34's speed target: the four-bar with 6
//! toleranced dimensions, 1e5 samples × 360 positions in ≤ 5 s): templates/fourbar-tolerances.toml's
//! model, the linear stack-up that fixes the histograms' ranges, then the Monte Carlo over
//! the whole motion on every thread, as `mechdraw run` computes it (without writing).

use serde::Serialize;

use crate::error::Error;
use crate::scene::{self, Scene};
use crate::solve::fourbar::solve_motion;
use crate::solve::tolerance::fourbar::{FourbarModel, FourbarOutput, FourbarPoint};
use crate::solve::tolerance::monte_carlo::{self, Model, chunk_count};
use crate::solve::tolerance::{Component, Projection, linear_all, ranges};

/// The template timed (embedded, so the command works from any directory).
pub const FOURBAR_TOLERANCES: &str = include_str!("../../templates/fourbar-tolerances.toml");

/// One timed Monte Carlo.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MonteCarloCost {
    /// The scene.
    pub scene: String,
    /// Samples drawn.
    pub samples: u64,
    /// Positions of the motion each sample is solved at.
    pub positions: usize,
    /// Toleranced dimensions.
    pub dimensions: usize,
    /// Components tallied per position.
    pub components: usize,
    /// Threads of the pool.
    pub threads: usize,
    /// Wall time of the Monte Carlo, seconds.
    pub wall_s: f64,
    /// Wall time per sample and position, nanoseconds.
    pub ns_per_sample_position: f64,
    /// Samples that could not be assembled somewhere (0 for the template).
    pub failed: u64,
}

/// Times the Monte Carlo of templates/fourbar-tolerances.toml with `samples` samples (its
/// own seed and bins; M's x, y, normal, along and the rocker's angle tallied).
pub fn fourbar_monte_carlo(samples: u64) -> Result<MonteCarloCost, Error> {
    let file = "fourbar-tolerances.toml";
    let Scene::Fourbar(s) = scene::parse(FOURBAR_TOLERANCES, file, &[])? else {
        return Err(Error::Export { what: file.into(), message: "not a four-bar scene".into() });
    };
    let Some(tol) = s.tolerances.as_ref() else {
        return Err(Error::Export { what: file.into(), message: "no [tolerances]".into() });
    };
    let motion = solve_motion(&s.spec).map_err(|e| Error::Solve { file: file.into(), source: e.into() })?;
    let outputs = vec![FourbarOutput::Point(FourbarPoint::M), FourbarOutput::Phi3];
    let model = FourbarModel::new(s.spec.geometry, &motion.positions, tol.study.params.clone(), outputs);
    let tangents = model.tangents(FourbarPoint::M);
    let normals = tangents.iter().map(|t| crate::geom::perp(*t)).collect();
    let comp = |name: &str, projection| Component {
        name: name.into(),
        output: name.into(),
        part: "value",
        absolute: false,
        projection,
    };
    let comps = vec![
        comp("M.x", Projection::Channel(0)),
        comp("M.y", Projection::Channel(1)),
        comp("M.normal", Projection::Along { x: 0, y: 1, dirs: normals }),
        comp("M.along", Projection::Along { x: 0, y: 1, dirs: tangents }),
        comp("phi3", Projection::Channel(2)),
    ];
    let dims = &tol.study.dims;
    let set = &tol.study.settings;
    let t0 = std::time::Instant::now();
    let linear = linear_all(&model, dims, &comps);
    let rs = ranges(&linear, comps.len());
    let mc = monte_carlo::run(&model, dims, &comps, &rs, set.bins, samples, set.seed, 0..chunk_count(samples));
    let wall_s = t0.elapsed().as_secs_f64();
    let positions = model.positions();
    Ok(MonteCarloCost {
        scene: s.name.clone(),
        samples,
        positions,
        dimensions: dims.len(),
        components: comps.len(),
        threads: rayon::current_num_threads(),
        wall_s,
        ns_per_sample_position: 1e9 * wall_s / (samples as f64 * positions.max(1) as f64),
        failed: mc.failed_samples,
    })
}

/// `tolerance.csv`: one row per timed Monte Carlo.
pub fn csv(rows: &[MonteCarloCost]) -> Vec<u8> {
    let mut s =
        String::from("scene,samples,positions,dimensions,components,threads,wall_s,ns_per_sample_position,failed\n");
    for r in rows {
        s.push_str(&format!(
            "{},{},{},{},{},{},{:.6},{:.2},{}\n",
            r.scene,
            r.samples,
            r.positions,
            r.dimensions,
            r.components,
            r.threads,
            r.wall_s,
            r.ns_per_sample_position,
            r.failed
        ));
    }
    s.into_bytes()
}
