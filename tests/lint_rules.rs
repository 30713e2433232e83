//! The math rules of the two clippy configurations agree: `clippy.toml` (every target, read by
//! `cargo clippy --all-targets`) and `.ci/core/clippy.toml` (the core for the browser, read
//! through `CLIPPY_CONF_DIR`) forbid the same `f64`/`f32` methods, so that neither the binary
//! nor the core calls the platform's math library (docs/ci.md: the same bits everywhere).

mod common;

use std::collections::BTreeMap;

/// The `f64::…`/`f32::…` entries of `disallowed-methods` in `file`: path → reason.
fn math_rules(file: &str) -> BTreeMap<String, String> {
    let text = std::fs::read_to_string(common::root().join(file)).unwrap();
    let table: toml::Table = text.parse().unwrap_or_else(|e| panic!("{file}: {e}"));
    table["disallowed-methods"]
        .as_array()
        .unwrap_or_else(|| panic!("{file}: no disallowed-methods"))
        .iter()
        .filter_map(|rule| {
            let path = rule["path"].as_str()?;
            (path.starts_with("f64::") || path.starts_with("f32::"))
                .then(|| (path.to_string(), rule["reason"].as_str().unwrap_or("").to_string()))
        })
        .collect()
}

#[test]
fn both_clippy_configurations_forbid_the_same_math() {
    let all = math_rules("clippy.toml");
    let core = math_rules(".ci/core/clippy.toml");
    assert_eq!(all, core, "clippy.toml and .ci/core/clippy.toml differ in their f64/f32 rules");
}

#[test]
fn every_transcendental_function_is_forbidden_for_both_float_types() {
    let rules = math_rules("clippy.toml");
    for name in [
        "sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sin_cos", "exp", "exp2", "exp_m1", "ln", "ln_1p", "log",
        "log2", "log10", "powf", "powi", "hypot", "sinh", "cosh", "tanh", "asinh", "acosh", "atanh", "cbrt",
    ] {
        for ty in ["f64", "f32"] {
            assert!(rules.contains_key(&format!("{ty}::{name}")), "{ty}::{name} is not forbidden");
        }
    }
    // Correctly rounded by IEEE 754 on every target: allowed (docs/ci.md says why).
    for allowed in ["f64::sqrt", "f64::mul_add", "f64::to_degrees", "f64::to_radians"] {
        assert!(!rules.contains_key(allowed), "{allowed} is forbidden");
    }
}
