//! `[tolerances]` on four-bar and linkage scenes (issue 34): which scene numbers are
//! toleranced (keys: the paths `--set` takes), each one's band and distribution, the watched
//! outputs (`[tolerances.outputs]`) and the study's settings (`[tolerances.settings]`).
//! Checked into [`Tolerances`], which holds the solver's [`Dimension`]s; each kind resolves
//! the paths and the output names (docs/tolerances.md).
//!
//! ```toml
//! [tolerances]
//! l1 = 0.00002                                   # ± t, in the field's unit
//! l_ab = { plus = 0.00003, minus = 0.00001 }     # + a / − b
//! l_bc = { upper = 0.00003, lower = -0.00001 }   # signed deviations, as a chain writes them
//! "o1[0]" = { tol = 0.00005, distribution = "uniform" }
//! c = [0.0001, { tol = 0.00005, cp = 1.33 }]   # c[0] and c[1]: a point's coordinates
//!
//! [tolerances.outputs]
//! points = ["M"]
//! angles = ["rocker"]
//!
//! [tolerances.settings]
//! samples = 100000        # Monte Carlo samples
//! seed = 1
//! distribution = "normal" # default of every dimension: normal, uniform, triangular
//! cp = 1.0                # normal: half band = 3·Cp·σ (or k = 3: half band = k·σ)
//! bins = 400              # histogram bins per component and position (percentiles)
//! trust = 0.1             # MC σ vs linear σ: a larger relative gap marks the position
//! magnification = 50      # the band drawing's deviations × this (default: chosen)
//! ```

use super::FieldError;
use crate::solve::tolerance::monte_carlo::MAX_SAMPLES;
use crate::solve::tolerance::{DEFAULT_BINS, DEFAULT_TRUST_FRACTION, Dimension, Distribution};

/// Default Monte Carlo samples.
pub const DEFAULT_SAMPLES: u64 = 100_000;
/// Most histogram bins per component and position.
pub const MAX_BINS: usize = 10_000;
/// Most memory the Monte Carlo's statistics may take, bytes (per thread, a histogram per
/// component and position): a scene asking for more is refused with the fields that set it.
pub const MAX_STATISTICS_BYTES: f64 = 2e9;
/// Threads the memory estimate assumes (each keeps its own statistics).
const THREADS_ESTIMATE: f64 = 4.0;

/// The watched outputs as a scene names them (each kind checks the names).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct OutputNames {
    /// Points (`M`; a linkage's `coupler.M`).
    pub points: Vec<String>,
    /// Bodies whose angle is watched (`rocker`).
    pub angles: Vec<String>,
    /// Points whose velocity, bodies whose angular velocity is watched (`M`, `rocker`).
    pub velocities: Vec<String>,
    /// Points whose acceleration, bodies whose angular acceleration is watched.
    pub accelerations: Vec<String>,
}

impl OutputNames {
    /// Whether nothing is named.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty() && self.angles.is_empty() && self.velocities.is_empty() && self.accelerations.is_empty()
    }
}

/// The study's settings.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// Monte Carlo samples (≥ 1).
    pub samples: u64,
    /// Random seed.
    pub seed: u64,
    /// Histogram bins per component and position.
    pub bins: usize,
    /// Relative gap between the Monte Carlo's σ and the linear σ beyond which a position
    /// is marked.
    pub trust: f64,
    /// The band drawing's magnification of the deviations (`None`: chosen).
    pub magnification: Option<f64>,
}

/// A checked `[tolerances]` table: the dimensions with the kind's handle on each (`P`).
#[derive(Debug, Clone, PartialEq)]
pub struct Tolerances<P> {
    /// The toleranced dimensions, in the file's order.
    pub dims: Vec<Dimension>,
    /// The kind's handle on each dimension (same order).
    pub params: Vec<P>,
    /// The watched outputs, as named.
    pub outputs: OutputNames,
    /// Settings.
    pub settings: Settings,
}

/// How a kind resolves a field path: the field's handle and nominal value, or the message
/// for a path that names no toleranced field.
pub type Resolve<'a, P> = &'a dyn Fn(&str) -> Result<(P, f64), String>;

/// What a kind tells the check: how a path resolves (its handle and nominal value, or
/// what would be valid) and how many positions the study watches.
pub struct Kind<'a, P> {
    /// The handle and nominal value of the field at a path, or the message for a path that
    /// names no toleranced field (what is wrong, what would be valid).
    pub resolve: Resolve<'a, P>,
    /// Positions of the motion (for the memory estimate).
    pub positions: usize,
    /// Components per watched point and per watched angle (for the memory estimate).
    pub components: (usize, usize),
}

fn err(field: impl Into<String>, message: impl Into<String>) -> FieldError {
    FieldError::new(field, message)
}

fn number(field: &str, v: &toml::Value) -> Result<f64, FieldError> {
    let x = match v {
        toml::Value::Float(f) => *f,
        toml::Value::Integer(i) => *i as f64,
        other => return Err(err(field, format!("must be a number, got {other}"))),
    };
    if x.is_finite() { Ok(x) } else { Err(err(field, format!("must be a finite number, got {x}"))) }
}

fn magnitude(field: &str, v: &toml::Value, what: &str) -> Result<f64, FieldError> {
    let x = number(field, v)?;
    if x < 0.0 {
        return Err(err(field, format!("must be ≥ 0 ({what}), got {x}")));
    }
    Ok(x)
}

/// The settings' distribution fields (`distribution`, `cp`, `k`) in `t` at `field`.
fn distribution(t: &toml::Table, field: &str, default: Option<Distribution>) -> Result<Distribution, FieldError> {
    let name = match t.get("distribution") {
        None => None,
        Some(toml::Value::String(s)) => Some(s.as_str()),
        Some(v) => {
            return Err(err(format!("{field}.distribution"), format!("must be a string, got {v}")));
        }
    };
    let (cp, k) = (t.get("cp"), t.get("k"));
    if cp.is_some() && k.is_some() {
        return Err(err(format!("{field}.k"), "give cp or k, not both (k = 3·cp)"));
    }
    let level = match (cp, k) {
        (Some(v), _) => Some(3.0 * positive_number(&format!("{field}.cp"), v)?),
        (_, Some(v)) => Some(positive_number(&format!("{field}.k"), v)?),
        _ => None,
    };
    let d = match (name, default) {
        (Some("normal"), _) => Distribution::Normal { k: level.unwrap_or(3.0) },
        (Some("uniform"), _) => Distribution::Uniform,
        (Some("triangular"), _) => Distribution::Triangular,
        (Some(other), _) => {
            return Err(err(
                format!("{field}.distribution"),
                format!("\"{other}\" is not a distribution; valid: \"normal\", \"uniform\", \"triangular\""),
            ));
        }
        (None, Some(Distribution::Normal { k })) => Distribution::Normal { k: level.unwrap_or(k) },
        (None, Some(d)) => d,
        (None, None) => Distribution::Normal { k: level.unwrap_or(3.0) },
    };
    if level.is_some() && !matches!(d, Distribution::Normal { .. }) {
        let which = if cp.is_some() { "cp" } else { "k" };
        return Err(err(format!("{field}.{which}"), "applies to a normal distribution only"));
    }
    Ok(d)
}

fn positive_number(field: &str, v: &toml::Value) -> Result<f64, FieldError> {
    let x = number(field, v)?;
    if x > 0.0 { Ok(x) } else { Err(err(field, format!("must be > 0, got {x}"))) }
}

/// One dimension's band (upper, lower deviation) and distribution.
fn band(field: &str, v: &toml::Value, default: Distribution) -> Result<(f64, f64, Distribution), FieldError> {
    let t = match v {
        toml::Value::Table(t) => t,
        v => {
            let t = magnitude(field, v, "a tolerance ± t; for +a/−b write { plus = a, minus = b }")?;
            return Ok((t, -t, default));
        }
    };
    const KEYS: [&str; 8] = ["tol", "plus", "minus", "upper", "lower", "distribution", "cp", "k"];
    if let Some(k) = t.keys().find(|k| !KEYS.contains(&k.as_str())) {
        return Err(err(
            format!("{field}.{k}"),
            "unknown field; valid: tol, plus and minus, upper and lower, distribution, cp, k",
        ));
    }
    let has = |k: &str| t.contains_key(k);
    let forms = [has("tol"), has("plus") || has("minus"), has("upper") || has("lower")];
    if forms.iter().filter(|f| **f).count() != 1 {
        return Err(err(
            field,
            "give the band one way: tol = t (± t), { plus = a, minus = b } (+a/−b), or { upper = a, lower = b } (signed deviations)",
        ));
    }
    let get = |k: &str| t.get(k).ok_or_else(|| err(format!("{field}.{k}"), "missing (give both ends of the band)"));
    let (upper, lower) = if forms[0] {
        let t = magnitude(&format!("{field}.tol"), get("tol")?, "the ± tolerance")?;
        (t, -t)
    } else if forms[1] {
        let a = magnitude(&format!("{field}.plus"), get("plus")?, "the size of the upper deviation +a")?;
        let b = magnitude(&format!("{field}.minus"), get("minus")?, "the size of the lower deviation −b")?;
        (a, -b)
    } else {
        let a = number(&format!("{field}.upper"), get("upper")?)?;
        let b = number(&format!("{field}.lower"), get("lower")?)?;
        if a < b {
            return Err(err(
                format!("{field}.upper"),
                format!(
                    "upper = {a} is below lower = {b}: swapped? (upper is the larger deviation, e.g. upper = {b}, lower = {a})"
                ),
            ));
        }
        (a, b)
    };
    Ok((upper, lower, distribution(t, field, Some(default))?))
}

fn names(field: &str, v: Option<&toml::Value>) -> Result<Vec<String>, FieldError> {
    match v {
        None => Ok(Vec::new()),
        Some(toml::Value::Array(a)) => a
            .iter()
            .enumerate()
            .map(|(i, x)| match x {
                toml::Value::String(s) => Ok(s.clone()),
                other => Err(err(format!("{field}[{i}]"), format!("must be a name (a string), got {other}"))),
            })
            .collect(),
        Some(other) => Err(err(field, format!("must be a list of names, got {other}"))),
    }
}

fn outputs(v: Option<&toml::Value>) -> Result<OutputNames, FieldError> {
    let Some(v) = v else { return Ok(OutputNames::default()) };
    let toml::Value::Table(t) = v else {
        return Err(err(
            "tolerances.outputs",
            "must be a table: points = [...], angles = [...], velocities = [...], accelerations = [...]",
        ));
    };
    const KEYS: [&str; 4] = ["points", "angles", "velocities", "accelerations"];
    if let Some(k) = t.keys().find(|k| !KEYS.contains(&k.as_str())) {
        return Err(err(format!("tolerances.outputs.{k}"), format!("unknown field; valid: {}", KEYS.join(", "))));
    }
    Ok(OutputNames {
        points: names("tolerances.outputs.points", t.get("points"))?,
        angles: names("tolerances.outputs.angles", t.get("angles"))?,
        velocities: names("tolerances.outputs.velocities", t.get("velocities"))?,
        accelerations: names("tolerances.outputs.accelerations", t.get("accelerations"))?,
    })
}

fn settings(v: Option<&toml::Value>) -> Result<(Settings, Distribution), FieldError> {
    let empty = toml::Table::new();
    let t = match v {
        None => &empty,
        Some(toml::Value::Table(t)) => t,
        Some(other) => return Err(err("tolerances.settings", format!("must be a table, got {other}"))),
    };
    const KEYS: [&str; 8] = ["samples", "seed", "bins", "distribution", "cp", "k", "trust", "magnification"];
    if let Some(k) = t.keys().find(|k| !KEYS.contains(&k.as_str())) {
        return Err(err(
            format!("tolerances.settings.{k}"),
            "unknown field; valid: samples, seed, bins, distribution, cp, k, trust, magnification",
        ));
    }
    let int = |k: &str| -> Result<Option<i64>, FieldError> {
        match t.get(k) {
            None => Ok(None),
            Some(toml::Value::Integer(i)) => Ok(Some(*i)),
            Some(other) => Err(err(format!("tolerances.settings.{k}"), format!("must be a whole number, got {other}"))),
        }
    };
    let samples = match int("samples")? {
        None => DEFAULT_SAMPLES,
        Some(n) if n >= 1 && (n as u64) <= MAX_SAMPLES => n as u64,
        Some(n) => {
            return Err(err(
                "tolerances.settings.samples",
                format!(
                    "must be between 1 and {MAX_SAMPLES} (2^32), got {n}; a larger study runs in shards (--shard K/N) of one seed"
                ),
            ));
        }
    };
    let seed = match int("seed")? {
        None => 1,
        Some(s) if s >= 0 => s as u64,
        Some(s) => return Err(err("tolerances.settings.seed", format!("must be ≥ 0, got {s}"))),
    };
    let bins = match int("bins")? {
        None => DEFAULT_BINS,
        Some(b) if b >= 10 && b as usize <= MAX_BINS => b as usize,
        Some(b) => return Err(err("tolerances.settings.bins", format!("must be between 10 and {MAX_BINS}, got {b}"))),
    };
    let trust = match t.get("trust") {
        None => DEFAULT_TRUST_FRACTION,
        Some(v) => {
            let x = positive_number("tolerances.settings.trust", v)?;
            if x >= 1.0 {
                return Err(err(
                    "tolerances.settings.trust",
                    format!("must be a fraction below 1 (e.g. 0.1), got {x}"),
                ));
            }
            x
        }
    };
    let magnification =
        t.get("magnification").map(|v| positive_number("tolerances.settings.magnification", v)).transpose()?;
    let dist = distribution(t, "tolerances.settings", None)?;
    Ok((Settings { samples, seed, bins, trust, magnification }, dist))
}

/// Whether a value is a band (a number, or a table with a band's key: `{ tol = …}`,
/// `{ plus = …, minus = … }`, …) rather than a step of a field's path.
fn is_band(v: &toml::Value) -> bool {
    const BAND: [&str; 8] = ["tol", "plus", "minus", "upper", "lower", "distribution", "cp", "k"];
    match v {
        // An empty table is a step with nothing under it (`body = [{}, { points.B = [t] }]`).
        toml::Value::Table(t) => t.keys().any(|k| BAND.contains(&k.as_str())),
        _ => true,
    }
}

/// The (path, field, band) entries under `path` (`field` names it in messages).
fn flatten<'a>(path: String, field: String, v: &'a toml::Value, out: &mut Vec<(String, String, &'a toml::Value)>) {
    match v {
        toml::Value::Array(items) => {
            for (i, item) in items.iter().enumerate() {
                flatten(format!("{path}[{i}]"), format!("{field}[{i}]"), item, out);
            }
        }
        toml::Value::Table(t) if !is_band(v) => {
            for (k, item) in t {
                flatten(format!("{path}.{k}"), format!("{field}.{k}"), item, out);
            }
        }
        v => out.push((path, field, v)),
    }
}

/// Checks a `[tolerances]` table for a kind.
pub fn check<P>(table: &toml::Table, kind: &Kind<'_, P>) -> Result<Tolerances<P>, FieldError> {
    let (settings, default) = settings(table.get("settings"))?;
    let outputs = outputs(table.get("outputs"))?;
    let mut dims = Vec::new();
    let mut params = Vec::new();
    // `"c[0]" = t` names one coordinate; `c = [t0, t1]` both (each item a band); a table
    // that is not a band is a step of the path (`ground.points.O = [t0, t1]`), as is an
    // array of such tables (`body = [{}, { points.B = [t0, t1] }]`).
    let mut entries: Vec<(String, String, &toml::Value)> = Vec::new();
    for (path, v) in table {
        if path == "settings" || path == "outputs" {
            continue;
        }
        // A leaf at the top is named quoted (`tolerances."l_ab"`), a path through arrays or
        // tables as the steps it takes (`tolerances.c[0]`, `tolerances.ground.points.O[1]`).
        let leaf = is_band(v) && !matches!(v, toml::Value::Array(_));
        let field = if leaf { format!("tolerances.\"{path}\"") } else { format!("tolerances.{path}") };
        flatten(path.clone(), field, v, &mut entries);
    }
    for (path, field, v) in entries {
        let (param, nominal) = (kind.resolve)(&path).map_err(|m| err(field.clone(), m))?;
        if dims.iter().any(|d: &Dimension| d.name == path) {
            return Err(err(field, "is toleranced twice"));
        }
        let (upper, lower, distribution) = band(&field, v, default)?;
        dims.push(Dimension { name: path, nominal, upper, lower, distribution });
        params.push(param);
    }
    if dims.is_empty() {
        return Err(err("tolerances", "names no toleranced field: add e.g. l_ab = 0.00005 (± t in the field's unit)"));
    }
    // A rate of a point has a point's components, at most.
    let components = (outputs.points.len().max(1) + outputs.velocities.len() + outputs.accelerations.len())
        * kind.components.0
        + outputs.angles.len() * kind.components.1;
    let bytes = kind.positions as f64 * components as f64 * (settings.bins as f64 + 2.0) * 8.0 * THREADS_ESTIMATE;
    if bytes > MAX_STATISTICS_BYTES {
        return Err(err(
            "tolerances.settings.bins",
            format!(
                "{} positions × {components} components × {} bins would keep {:.1} GB of statistics (at most {:.0} GB): use fewer bins or positions",
                kind.positions,
                settings.bins,
                bytes / 1e9,
                MAX_STATISTICS_BYTES / 1e9
            ),
        ));
    }
    Ok(Tolerances { dims, params, outputs, settings })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kind_check(text: &str) -> Result<Tolerances<()>, FieldError> {
        let t: toml::Table = text.parse().unwrap();
        let resolve = |p: &str| if p == "a" || p == "b" { Ok(((), 1.0)) } else { Err("no such field".to_string()) };
        check(&t, &Kind { resolve: &resolve, positions: 360, components: (4, 1) })
    }

    #[test]
    fn bands_in_every_form() {
        let t = kind_check("a = 0.1\nb = { plus = 0.2, minus = 0.1, distribution = \"uniform\" }\n").unwrap();
        assert_eq!((t.dims[0].upper, t.dims[0].lower), (0.1, -0.1));
        assert_eq!((t.dims[1].upper, t.dims[1].lower), (0.2, -0.1));
        assert_eq!(t.dims[1].distribution, Distribution::Uniform);
        let t = kind_check("a = { upper = 0.2, lower = 0.1, cp = 1.5 }\n").unwrap();
        // The array form names indexed fields.
        let arr: toml::Table = "p = [0.1, { tol = 0.2 }]\n".parse().unwrap();
        let resolve = |p: &str| if p == "p[0]" || p == "p[1]" { Ok(((), 1.0)) } else { Err("no".to_string()) };
        let k = check(&arr, &Kind { resolve: &resolve, positions: 10, components: (4, 1) }).unwrap();
        assert_eq!(k.dims.iter().map(|d| d.name.as_str()).collect::<Vec<_>>(), ["p[0]", "p[1]"]);
        assert_eq!(k.dims[1].upper, 0.2);
        assert_eq!((t.dims[0].upper, t.dims[0].lower), (0.2, 0.1));
        assert_eq!(t.dims[0].distribution, Distribution::Normal { k: 4.5 });
        assert_eq!(t.settings.samples, DEFAULT_SAMPLES);
    }

    #[test]
    fn bad_input_names_the_field() {
        let field = |text: &str| kind_check(text).unwrap_err().field;
        assert_eq!(field("zz = 0.1\n"), "tolerances.\"zz\"");
        assert_eq!(field("a = -0.1\n"), "tolerances.\"a\"");
        assert_eq!(field("a = \"x\"\n"), "tolerances.\"a\"");
        assert_eq!(field("a = { upper = -0.1, lower = 0.1 }\n"), "tolerances.\"a\".upper");
        assert_eq!(field("a = { plus = 0.1 }\n"), "tolerances.\"a\".minus");
        assert_eq!(field("a = 0.1\n[settings]\nsamples = 0\n"), "tolerances.settings.samples");
        assert_eq!(field("a = 0.1\n[settings]\nbins = 10001\n"), "tolerances.settings.bins");
        assert_eq!(field("a = 0.1\n[settings]\nsamples = 99999999999\n"), "tolerances.settings.samples");
        assert_eq!(field("a = { tol = 0.1, distribution = \"uniform\", cp = 1 }\n"), "tolerances.\"a\".cp");
        assert_eq!(field("[settings]\nseed = 1\n"), "tolerances");
    }
}
