//! Seed 001 (Humienny 1989): matrices (2) and (3) describe one part; coordinates,
//! correctness and dimensional functions checked against values derived by hand from the
//! printed matrices.

mod common;

use mechdraw::scene::{self, Scene};
use mechdraw::solve::chain::{Analysis, Chain, Function, Term, analyse};

/// The checked scene's chain: the solver's input.
fn load(text: &str) -> Chain {
    match scene::parse(text, "t.toml", &[]).unwrap() {
        Scene::Chain(c) => c.chain,
        _ => unreachable!(),
    }
}

fn template(name: &str) -> String {
    std::fs::read_to_string(common::root().join("templates").join(name)).unwrap()
}

fn sorted(mut v: Vec<f64>) -> Vec<f64> {
    v.sort_by(f64::total_cmp);
    v
}

fn functions(s: &Chain, a: &Analysis) -> Vec<Function> {
    s.dependent.iter().map(|z| a.function(s, z).unwrap()).collect()
}

fn terms(pairs: &[(usize, f64)]) -> Vec<Term> {
    pairs.iter().map(|&(dim, coef)| Term { dim, coef }).collect()
}

#[test]
fn matrix_2_gives_the_nine_feature_coordinates_and_no_redundancy() {
    // Matrix (2): B = [0, 0, -38, -38, 260, -100, -100, 65], W = [-38, 25, 80, 260, -100, 55, 65, 15].
    // By hand, from the zero point 0:
    //   w1 = -38 from 0            → -38
    //   w2 =  25 from 0            →  25
    //   w3 =  80 from end of -38   → -38 + 80  =  42
    //   w4 = 260 from end of -38   → -38 + 260 = 222
    //   w5 = -100 from end of 260  → 222 - 100 = 122
    //   w6 =  55 from end of -100  → 122 + 55  = 177
    //   w7 =  65 from end of -100  → 122 + 65  = 187
    //   w8 =  15 from end of 65    → 187 + 15  = 202
    let s = load(&template("chain-humienny-2.toml"));
    let a = analyse(&s);
    let xs = sorted(a.features.iter().map(|f| f.x).collect());
    assert_eq!(xs, sorted(vec![0.0, -38.0, 25.0, 42.0, 222.0, 122.0, 177.0, 187.0, 202.0]));
    // k = 9 features, n = 8 dimensions, one group: n − k + 1 = 0 redundant (the seed's test:
    // no two coordinates coincide).
    assert_eq!(a.features.len(), 9);
    assert!(a.redundant.is_empty());
    assert!(a.coincident.is_empty());
    assert!(a.untied.is_empty());
    assert_eq!(a.redundant_count(8), 0);
}

#[test]
fn matrix_3_is_the_same_part_shifted() {
    // Matrix (3): B = [-260, 38, -260, 100, 0, 0, 0, 65], W = [38, 25, 80, -260, 100, 55, 65, 15].
    // By hand: w5 = 100, w6 = 55, w7 = 65 from 0; w4 = -260 from end of 100 → -160;
    // w1 = 38 and w3 = 80 from end of -260 → -122, -80; w2 = 25 from end of 38 → -97;
    // w8 = 15 from end of 65 → 80. These are the coordinates of (2) minus 122: the zero point
    // of (3) is the end of -100 in (2).
    let s2 = load(&template("chain-humienny-2.toml"));
    let s3 = load(&template("chain-humienny-3.toml"));
    let (a2, a3) = (analyse(&s2), analyse(&s3));
    let x3 = sorted(a3.features.iter().map(|f| f.x).collect());
    assert_eq!(x3, sorted(vec![0.0, 100.0, 55.0, 65.0, -160.0, -122.0, -80.0, -97.0, 80.0]));
    let x2_shifted = sorted(a2.features.iter().map(|f| f.x - 122.0).collect());
    assert_eq!(x3, x2_shifted);
    assert!(a3.redundant.is_empty() && a3.untied.is_empty());
    // The template's dependent dimensions name the same features in both matrices: same Z.
    let f2 = functions(&s2, &a2);
    let f3 = functions(&s3, &a3);
    for (a, b) in f2.iter().zip(&f3) {
        assert_eq!(a.nominal, b.nominal);
        assert_eq!(a.terms.len(), b.terms.len());
    }
}

#[test]
fn dependent_dimensions_of_the_seed_have_the_right_functions() {
    let s = load(&template("chain-humienny-2.toml"));
    let a = analyse(&s);
    let f = functions(&s, &a);
    let dims = &s.dimensions;
    // Z = [25, 80]: x(end of 80) − x(end of 25) = (w1 + w3) − w2 = −38 + 80 − 25 = 17.
    assert_eq!(f[0].terms, terms(&[(0, 1.0), (1, -1.0), (2, 1.0)]));
    assert_eq!(f[0].nominal, 17.0);
    assert_eq!(f[0].equation("Z1", dims), "Z1 = w1 - w2 + w3 = (-38) - 25 + 80 = 17");
    // Z = [0, 80]: x(end of 80) − 0 = w1 + w3 = 42.
    assert_eq!(f[1].terms, terms(&[(0, 1.0), (2, 1.0)]));
    assert_eq!(f[1].nominal, 42.0);
    // Z = [-38, 55]: (w1 + w4 + w5 + w6) − w1 = w4 + w5 + w6 = 260 − 100 + 55 = 215.
    assert_eq!(f[2].terms, terms(&[(3, 1.0), (4, 1.0), (5, 1.0)]));
    assert_eq!(f[2].nominal, 215.0);
    // Z = [80, -100]: (w1 + w4 + w5) − (w1 + w3) = −w3 + w4 + w5 = −80 + 260 − 100 = 80.
    assert_eq!(f[3].terms, terms(&[(2, -1.0), (3, 1.0), (4, 1.0)]));
    assert_eq!(f[3].nominal, 80.0);
}

#[test]
fn matrix_3_functions_use_its_own_dimensions() {
    let s = load(&template("chain-humienny-3.toml"));
    let a = analyse(&s);
    let f = functions(&s, &a);
    // Z = [25, 80] in (3): x(80) = w5 + w4 + w3, x(25) = w5 + w4 + w1 + w2 → Z = −w1 − w2 + w3
    // = −38 − 25 + 80 = 17.
    assert_eq!(f[0].terms, terms(&[(0, -1.0), (1, -1.0), (2, 1.0)]));
    assert_eq!(f[0].nominal, 17.0);
    // Z = [38, 80]: x(80) − x(38) = w3 − w1 = 42.
    assert_eq!(f[1].terms, terms(&[(0, -1.0), (2, 1.0)]));
    assert_eq!(f[1].nominal, 42.0);
    // Z = [-260, 55]: w6 − (w5 + w4) = 55 − 100 + 260 = 215.
    assert_eq!(f[2].terms, terms(&[(3, -1.0), (4, -1.0), (5, 1.0)]));
    assert_eq!(f[2].nominal, 215.0);
}

#[test]
fn the_named_form_of_the_same_part_gives_the_same_functions() {
    // Fig. 1 with named features: a zero point O and surfaces A..H, dimensions as in (2).
    let text = r#"
kind = "chain"
name = "named"
units = "mm"
features = ["O", "A", "B", "C", "D", "E", "F", "G", "H"]
dependent = [["B", "C"], ["O", "C"], ["A", "F"]]
[[dimension]]
from = "O"
to = "A"
nominal = -38
tol = 0.1
[[dimension]]
from = "O"
to = "B"
nominal = 25
tol = 0.1
[[dimension]]
from = "A"
to = "C"
nominal = 80
tol = 0.1
[[dimension]]
from = "A"
to = "D"
nominal = 260
tol = 0.1
[[dimension]]
from = "D"
to = "E"
nominal = -100
tol = 0.1
[[dimension]]
from = "E"
to = "F"
nominal = 55
tol = 0.1
[[dimension]]
from = "E"
to = "G"
nominal = 65
tol = 0.1
[[dimension]]
from = "G"
to = "H"
nominal = 15
tol = 0.1
"#;
    let s = load(text);
    let a = analyse(&s);
    let named = functions(&s, &a);
    let s2 = load(&template("chain-humienny-2.toml"));
    let a2 = analyse(&s2);
    let matrix = functions(&s2, &a2);
    for (n, m) in named.iter().zip(&matrix) {
        assert_eq!(n, m);
    }
    let xs = sorted(a.features.iter().map(|f| f.x).collect());
    assert_eq!(xs, sorted(a2.features.iter().map(|f| f.x).collect()));
}
