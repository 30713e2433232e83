//! Scene kind `chain`: a system of parallel dimensional chains (seed 001, Humienny 1989).
//!
//! Two input forms, one checked scene:
//!
//! - the seed's matrix N: `B` (bases) and `W` (signed dimensions), `tol` one value or one per
//!   dimension. A base is `0` (the zero point) or the value of the dimension whose end point
//!   it starts from; dependent dimensions are `[b_l, b_p]` pairs of such values (eq. 4);
//! - named features: `features = ["A", ...]` and `[[dimension]]` tables between two named
//!   features with a nominal value and a tolerance (`tol`, or `upper`/`lower`); dependent
//!   dimensions are pairs of feature names.
//!
//! Matrix references are resolved by value here (an ambiguous or dangling base is a field
//! error); the graph (features = nodes, dimensions = edges) is built by the solver.

use serde::Deserialize;

use super::{FieldError, Units};
pub use crate::solve::chain::{Chain, Dependent, Dimension, Distribution, Form};

/// Largest Monte Carlo sample count accepted per dependent dimension (memory: 8 bytes each).
pub const MAX_SAMPLES: u64 = 20_000_000;
/// Two matrix values are the same reference when they differ by less than this (model
/// units): well below the seed's 0.0001 mm perturbation of equal nominal values.
pub const VALUE_MATCH_TOL: f64 = 1e-9;

/// A feature reference in a dependent dimension: a base value (matrix form) or a name.
#[derive(Debug, Clone, Deserialize)]
#[serde(untagged)]
pub enum RawRef {
    /// Matrix form: `0` or the value of a dimension in `W`.
    Value(f64),
    /// Named form: a feature name.
    Name(String),
}

/// A dependent dimension as written: `[left, right]` or a table.
#[derive(Debug, Clone, Deserialize)]
#[serde(untagged)]
pub enum RawDependent {
    /// `[b_l, b_p]`.
    Pair([RawRef; 2]),
    /// `{ between = [b_l, b_p], name = "Z1", spec = [LSL, USL] }`.
    Table(RawDependentTable),
}

/// The table form of a dependent dimension.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawDependentTable {
    /// Left and right end (`[b_l, b_p]`).
    pub between: [RawRef; 2],
    /// Name in reports (default `Z1`, `Z2`, ... by position).
    pub name: Option<String>,
    /// Specification limits `[LSL, USL]` on Z (absolute values).
    pub spec: Option<[f64; 2]>,
}

/// `tol` in the matrix form: one value for all, or one per dimension.
#[derive(Debug, Clone, Deserialize)]
#[serde(untagged)]
pub enum RawTol {
    /// The same symmetric tolerance ± for every dimension.
    All(f64),
    /// One symmetric tolerance ± per dimension, in `W` order.
    Each(Vec<f64>),
}

/// A dimension of the named form.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawDimension {
    /// Name in reports and the dimensional function (default `w1`, `w2`, ...).
    pub name: Option<String>,
    /// Feature the dimension starts from (its base).
    pub from: String,
    /// Feature the dimension ends at.
    pub to: String,
    /// Nominal value x_to − x_from (signed, like the seed's W).
    pub nominal: f64,
    /// Symmetric tolerance ±tol.
    pub tol: Option<f64>,
    /// Upper deviation of the dimension's size (e.g. +0.1).
    pub upper: Option<f64>,
    /// Lower deviation of the dimension's size (e.g. −0.05).
    pub lower: Option<f64>,
}

/// `[stackup]` as written.
#[derive(Debug, Clone, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct RawStackup {
    /// Factor of the modified RSS method (default 1.5).
    pub mrss_factor: Option<f64>,
    /// Monte Carlo distribution (default normal).
    pub distribution: Option<Distribution>,
    /// Monte Carlo sample count (default 100000; 0 skips Monte Carlo).
    pub samples: Option<u64>,
    /// Seed of the random generator (default 1).
    pub seed: Option<u64>,
    /// Histogram bins (default 40).
    pub bins: Option<u32>,
}

/// The scene as written in the file (`kind` removed).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawChainScene {
    /// Output file stem.
    pub name: String,
    /// Length units.
    pub units: Units,
    /// Matrix form: row B of bases.
    #[serde(rename = "B")]
    pub b: Option<Vec<f64>>,
    /// Matrix form: row W of signed dimensions.
    #[serde(rename = "W")]
    pub w: Option<Vec<f64>>,
    /// Matrix form: symmetric tolerances.
    pub tol: Option<RawTol>,
    /// Named form: feature names; the first one is the zero point.
    pub features: Option<Vec<String>>,
    /// Named form: dimensions between features.
    pub dimension: Option<Vec<RawDimension>>,
    /// Dependent dimensions to analyse.
    #[serde(default)]
    pub dependent: Vec<RawDependent>,
    /// Stack-up settings.
    #[serde(default)]
    pub stackup: RawStackup,
}

/// Checked stack-up settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stackup {
    /// Factor of the modified RSS (> 0).
    pub mrss_factor: f64,
    /// Monte Carlo distribution.
    pub distribution: Distribution,
    /// Monte Carlo samples (0 = none).
    pub samples: u64,
    /// Random seed.
    pub seed: u64,
    /// Histogram bins (≥ 1).
    pub bins: u32,
}

/// A checked `chain` scene: the solver's chain (features, dimensions between them,
/// dependent dimensions) with its name, units and stack-up settings.
#[derive(Debug, Clone)]
pub struct ChainScene {
    /// Output file stem.
    pub name: String,
    /// Length units.
    pub units: Units,
    /// The solver's input: form, features, dimensions, dependent dimensions.
    pub chain: Chain,
    /// Stack-up settings.
    pub stackup: Stackup,
}

/// Formats a matrix value the way the seed writes it (`80`, `-38`, `50.001`).
pub fn value_label(v: f64) -> String {
    let s = format!("{v}");
    if s == "-0" { "0".into() } else { s }
}

/// Validates the raw scene.
pub fn check(raw: RawChainScene) -> Result<ChainScene, FieldError> {
    let name = super::check_name(&raw.name)?;
    let stackup = check_stackup(&raw.stackup)?;
    let matrix = raw.b.is_some() || raw.w.is_some();
    let named = raw.features.is_some() || raw.dimension.is_some();
    let (form, features, dimensions, dependent) = match (matrix, named) {
        (true, true) => {
            return Err(FieldError::new(
                if raw.features.is_some() { "features" } else { "dimension" },
                "a chain is given either as the matrix (B, W, tol) or as named features (features, [[dimension]]), not both",
            ));
        }
        (false, false) => {
            return Err(FieldError::new(
                "W",
                "missing: give the matrix N as B = [...] and W = [...], or named features as features = [...] and [[dimension]] tables",
            ));
        }
        (true, false) => {
            let (features, dims) = check_matrix(&raw)?;
            let dependent = check_dependents(&raw.dependent, |i, j, r| matrix_ref(&dims, i, j, r))?;
            (Form::Matrix, features, dims, dependent)
        }
        (false, true) => {
            if raw.tol.is_some() {
                return Err(FieldError::new(
                    "tol",
                    "the named form gives tolerances per [[dimension]] (tol, or upper and lower)",
                ));
            }
            let (features, dims) = check_named(&raw)?;
            let dependent = check_dependents(&raw.dependent, |i, j, r| named_ref(&features, i, j, r))?;
            (Form::Named, features, dims, dependent)
        }
    };
    Ok(ChainScene { name, units: raw.units, chain: Chain { form, features, dimensions, dependent }, stackup })
}

fn check_stackup(raw: &RawStackup) -> Result<Stackup, FieldError> {
    let mrss_factor = match raw.mrss_factor {
        None => 1.5,
        Some(f) if f.is_finite() && f > 0.0 => f,
        Some(f) => {
            return Err(FieldError::new(
                "stackup.mrss_factor",
                format!("must be a positive number (1.5 is usual), got {f}"),
            ));
        }
    };
    let samples = raw.samples.unwrap_or(100_000);
    if samples > MAX_SAMPLES {
        return Err(FieldError::new(
            "stackup.samples",
            format!("{samples} is too many: at most {MAX_SAMPLES} (0 skips Monte Carlo)"),
        ));
    }
    let bins = raw.bins.unwrap_or(40);
    if bins == 0 || bins > 1000 {
        return Err(FieldError::new("stackup.bins", format!("must be 1 to 1000, got {bins}")));
    }
    Ok(Stackup {
        mrss_factor,
        distribution: raw.distribution.unwrap_or_default(),
        samples,
        seed: raw.seed.unwrap_or(1),
        bins,
    })
}

fn check_tol(field: &str, t: f64) -> Result<f64, FieldError> {
    super::non_negative_within(field, t, super::MAX_LENGTH, "a tolerance (the ± value, in the scene's unit)")
}

/// The matrix form: feature 0 = zero point, feature i+1 = end point of W[i].
fn check_matrix(raw: &RawChainScene) -> Result<(Vec<String>, Vec<Dimension>), FieldError> {
    let w = raw.w.as_ref().ok_or_else(|| FieldError::new("W", "missing: row W of signed dimensions (B is given)"))?;
    let b = raw.b.as_ref().ok_or_else(|| FieldError::new("B", "missing: row B of bases (W is given)"))?;
    if w.is_empty() {
        return Err(FieldError::new("W", "must hold at least one dimension"));
    }
    if b.len() != w.len() {
        return Err(FieldError::new(
            "B",
            format!(
                "has {} bases but W has {} dimensions: the matrix N is 2×n, one base per dimension",
                b.len(),
                w.len()
            ),
        ));
    }
    for (i, v) in w.iter().enumerate() {
        let f = format!("W[{i}]");
        super::length(&f, *v)?;
        if v.abs() < VALUE_MATCH_TOL {
            return Err(FieldError::new(
                f,
                "is 0: a dimension needs a nonzero signed value (0 is reserved for the zero point)",
            ));
        }
    }
    let tols: Vec<f64> = match &raw.tol {
        None => vec![0.0; w.len()],
        Some(RawTol::All(t)) => vec![check_tol("tol", *t)?; w.len()],
        Some(RawTol::Each(ts)) => {
            if ts.len() != w.len() {
                return Err(FieldError::new(
                    "tol",
                    format!(
                        "has {} values but W has {} dimensions: give one tolerance, or one per dimension",
                        ts.len(),
                        w.len()
                    ),
                ));
            }
            ts.iter().enumerate().map(|(i, t)| check_tol(&format!("tol[{i}]"), *t)).collect::<Result<_, _>>()?
        }
    };
    let mut features = vec!["0".to_string()];
    features.extend(w.iter().map(|v| value_label(*v)));
    let mut dims = Vec::with_capacity(w.len());
    for (i, (&base, &value)) in b.iter().zip(w).enumerate() {
        let field = format!("B[{i}]");
        super::length(&field, base)?;
        let from = resolve_value(w, base).map_err(|m| FieldError::new(field.clone(), m))?;
        if from == i + 1 {
            return Err(FieldError::new(
                field,
                format!(
                    "{} is the dimension's own value: a dimension cannot start from its own end point",
                    value_label(base)
                ),
            ));
        }
        dims.push(Dimension {
            name: format!("w{}", i + 1),
            from,
            to: i + 1,
            nominal: value,
            upper: tols[i],
            lower: -tols[i],
        });
    }
    Ok((features, dims))
}

/// Feature index of a matrix value: 0 for the zero point, else i+1 for the dimension W[i]
/// of that value. The message says what is wrong.
fn resolve_value(w: &[f64], v: f64) -> Result<usize, String> {
    if v.abs() < VALUE_MATCH_TOL {
        return Ok(0);
    }
    let hits: Vec<usize> =
        w.iter().enumerate().filter(|(_, x)| (**x - v).abs() < VALUE_MATCH_TOL).map(|(i, _)| i).collect();
    match hits.as_slice() {
        [i] => Ok(i + 1),
        [] => {
            let valid: Vec<String> = w.iter().map(|x| value_label(*x)).collect();
            // The seed's own examples (5) write Z1 = [80, 100] for the dimension -100: say so.
            let flipped = w.iter().find(|x| (**x + v).abs() < VALUE_MATCH_TOL);
            let hint = flipped.map_or(String::new(), |x| format!("; did you mean {} (signs count)?", value_label(*x)));
            Err(format!(
                "{} refers to no dimension: a base is 0 (the zero point) or the value of a dimension in W ({}){hint}",
                value_label(v),
                valid.join(", ")
            ))
        }
        many => {
            let at: Vec<String> = many.iter().map(|i| format!("W[{i}]")).collect();
            Err(format!(
                "{} is ambiguous: {} all have this value. The seed tells equal dimensions apart by perturbing them \
                 (50.000, 50.001, ...); better, describe the chain with named features: \
                 features = [\"A\", \"B\", ...] and [[dimension]] from = \"A\", to = \"B\", nominal = ..., tol = ...",
                value_label(v),
                at.join(", ")
            ))
        }
    }
}

fn matrix_ref(dims: &[Dimension], i: usize, j: usize, r: &RawRef) -> Result<usize, FieldError> {
    let field = format!("dependent[{i}][{j}]");
    match r {
        RawRef::Value(v) => {
            let w: Vec<f64> = dims.iter().map(|d| d.nominal).collect();
            super::length(&field, *v)?;
            resolve_value(&w, *v).map_err(|m| FieldError::new(field, m))
        }
        RawRef::Name(n) => Err(FieldError::new(
            field,
            format!("\"{n}\" is a name, but this chain is a matrix: an end is 0 or the value of a dimension in W"),
        )),
    }
}

fn named_ref(features: &[String], i: usize, j: usize, r: &RawRef) -> Result<usize, FieldError> {
    let field = format!("dependent[{i}][{j}]");
    match r {
        RawRef::Name(n) => feature_index(features, &field, n),
        RawRef::Value(v) => Err(FieldError::new(
            field,
            format!("{v} is a number, but this chain has named features: use one of {}", features.join(", ")),
        )),
    }
}

fn feature_index(features: &[String], field: &str, n: &str) -> Result<usize, FieldError> {
    features.iter().position(|f| f == n).ok_or_else(|| {
        FieldError::new(field, format!("\"{n}\" is not a feature: valid features are {}", features.join(", ")))
    })
}

fn check_dependents(
    raw: &[RawDependent],
    resolve: impl Fn(usize, usize, &RawRef) -> Result<usize, FieldError>,
) -> Result<Vec<Dependent>, FieldError> {
    let mut out = Vec::with_capacity(raw.len());
    let mut names: Vec<String> = Vec::new();
    for (i, d) in raw.iter().enumerate() {
        let (ends, name, spec) = match d {
            RawDependent::Pair(e) => (e, None, None),
            RawDependent::Table(t) => (&t.between, t.name.clone(), t.spec),
        };
        let left = resolve(i, 0, &ends[0])?;
        let right = resolve(i, 1, &ends[1])?;
        let name = name.unwrap_or_else(|| format!("Z{}", i + 1));
        // It names the dimension's histogram, diagrams/<scene>/<name>-histogram.svg.
        let name = super::check_file_name(&format!("dependent[{i}].name"), &name)?;
        if names.contains(&name) {
            return Err(FieldError::new(format!("dependent[{i}].name"), format!("\"{name}\" is used twice")));
        }
        names.push(name.clone());
        if let Some([lsl, usl]) = spec
            && !(lsl.is_finite() && usl.is_finite() && lsl < usl && lsl.abs().max(usl.abs()) <= super::MAX_LENGTH)
        {
            return Err(FieldError::new(
                format!("dependent[{i}].spec"),
                format!(
                    "must be [LSL, USL] with LSL < USL, each from -{max:e} to {max:e}, got [{lsl:?}, {usl:?}]",
                    max = super::MAX_LENGTH
                ),
            ));
        }
        let label = |r: &RawRef| match r {
            RawRef::Value(v) => value_label(*v),
            RawRef::Name(n) => n.clone(),
        };
        out.push(Dependent { name, left, right, label: format!("[{}, {}]", label(&ends[0]), label(&ends[1])), spec });
    }
    Ok(out)
}

/// The named form.
fn check_named(raw: &RawChainScene) -> Result<(Vec<String>, Vec<Dimension>), FieldError> {
    let features = raw.features.clone().ok_or_else(|| {
        FieldError::new(
            "features",
            "missing: list the feature names, the zero point first: features = [\"A\", \"B\", ...]",
        )
    })?;
    if features.len() < 2 {
        return Err(FieldError::new("features", "needs at least two features"));
    }
    for (i, f) in features.iter().enumerate() {
        if f.trim().is_empty() {
            return Err(FieldError::new(format!("features[{i}]"), "is empty: give each feature a name"));
        }
        if features[..i].contains(f) {
            return Err(FieldError::new(format!("features[{i}]"), format!("\"{f}\" is listed twice")));
        }
    }
    let raw_dims = raw.dimension.as_ref().ok_or_else(|| {
        FieldError::new("dimension", "missing: add [[dimension]] tables with from, to, nominal and tol")
    })?;
    let mut dims = Vec::with_capacity(raw_dims.len());
    for (i, d) in raw_dims.iter().enumerate() {
        let at = |k: &str| format!("dimension[{i}].{k}");
        let from = feature_index(&features, &at("from"), &d.from)?;
        let to = feature_index(&features, &at("to"), &d.to)?;
        if from == to {
            return Err(FieldError::new(at("to"), format!("is the same feature as from (\"{}\")", d.to)));
        }
        let nominal = super::length(&at("nominal"), d.nominal)?;
        if nominal.abs() < VALUE_MATCH_TOL {
            return Err(FieldError::new(at("nominal"), "is 0: two features at the same place are one feature"));
        }
        let (upper, lower) = match (d.tol, d.upper, d.lower) {
            (Some(t), None, None) => {
                let t = check_tol(&at("tol"), t)?;
                (t, -t)
            }
            (None, Some(u), Some(l)) => {
                let u = super::length(&at("upper"), u)?;
                let l = super::length(&at("lower"), l)?;
                if l > u {
                    return Err(FieldError::new(at("lower"), format!("{l} is above upper = {u}")));
                }
                (u, l)
            }
            (None, None, None) => (0.0, 0.0),
            (Some(_), _, _) => {
                return Err(FieldError::new(at("tol"), "give either tol (±) or upper and lower, not both"));
            }
            (None, Some(_), None) => {
                return Err(FieldError::new(at("lower"), "missing: upper is given, so lower is needed too"));
            }
            (None, None, Some(_)) => {
                return Err(FieldError::new(at("upper"), "missing: lower is given, so upper is needed too"));
            }
        };
        let name = d.name.clone().unwrap_or_else(|| format!("w{}", i + 1));
        if name.trim().is_empty() || dims.iter().any(|x: &Dimension| x.name == name) {
            return Err(FieldError::new(at("name"), format!("\"{name}\" is empty or used twice")));
        }
        dims.push(Dimension { name, from, to, nominal, upper, lower });
    }
    if dims.is_empty() {
        return Err(FieldError::new("dimension", "needs at least one [[dimension]]"));
    }
    Ok((features, dims))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Scene, SceneError, parse};

    fn chain(text: &str) -> Result<ChainScene, SceneError> {
        parse(text, "t.toml", &[]).map(|s| match s {
            Scene::Chain(c) => c,
            _ => unreachable!(),
        })
    }

    #[test]
    fn matrix_bases_resolve_to_the_end_points_of_dimensions_by_value() {
        let c = chain("kind='chain'\nname='c'\nunits='mm'\nB=[0,0,-38]\nW=[-38,25,80]\ntol=0.1\ndependent=[[25,80]]")
            .unwrap();
        assert_eq!(c.chain.dimensions[2].from, 1); // based on the end of -38 (feature 1)
        assert_eq!(c.chain.dependent[0].left, 2);
        assert_eq!(c.chain.dependent[0].right, 3);
        assert_eq!(c.chain.features, ["0", "-38", "25", "80"]);
    }

    #[test]
    fn a_dangling_base_names_the_field_and_the_valid_values() {
        let e = chain("kind='chain'\nname='c'\nunits='mm'\nB=[0,99]\nW=[-38,25]").unwrap_err().to_string();
        assert!(e.contains("field `B[1]`") && e.contains("99 refers to no dimension") && e.contains("-38, 25"), "{e}");
    }

    #[test]
    fn a_dimension_based_on_itself_is_refused() {
        let e = chain("kind='chain'\nname='c'\nunits='mm'\nB=[0,25]\nW=[-38,25]").unwrap_err().to_string();
        assert!(e.contains("field `B[1]`") && e.contains("own end point"), "{e}");
    }

    #[test]
    fn a_base_with_the_wrong_sign_gets_a_hint() {
        let e = chain("kind='chain'\nname='c'\nunits='mm'\nB=[0,0]\nW=[-100,25]\ndependent=[[25,100]]")
            .unwrap_err()
            .to_string();
        assert!(e.contains("dependent[0][1]") && e.contains("did you mean -100"), "{e}");
    }

    #[test]
    fn an_ambiguous_base_points_to_the_named_form() {
        let e = chain("kind='chain'\nname='c'\nunits='mm'\nB=[0,0,50]\nW=[50,50,10]").unwrap_err().to_string();
        assert!(e.contains("field `B[2]`") && e.contains("ambiguous") && e.contains("[[dimension]]"), "{e}");
    }

    #[test]
    fn named_form_reads_asymmetric_tolerances() {
        let c = chain(
            "kind='chain'\nname='c'\nunits='mm'\nfeatures=['A','B']\n[[dimension]]\nfrom='A'\nto='B'\nnominal=10\nupper=0.1\nlower=-0.05",
        )
        .unwrap();
        assert_eq!((c.chain.dimensions[0].upper, c.chain.dimensions[0].lower), (0.1, -0.05));
        assert!((c.chain.dimensions[0].mid() - 0.025).abs() < 1e-15);
        let e = chain(
            "kind='chain'\nname='c'\nunits='mm'\nfeatures=['A','B']\n[[dimension]]\nfrom='A'\nto='C'\nnominal=10",
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("dimension[0].to") && e.contains("\"C\" is not a feature"), "{e}");
    }
}
