//! Golden pictures of the chain: the drawing of matrix (2) (SVG rasterised) and its DXF
//! (ezdxf audit clean, compared line by line).

mod common;

use std::path::PathBuf;

/// Runs a template into a fresh directory and returns it.
fn run(template: &str, extra: &[&str]) -> (tempfile::TempDir, PathBuf) {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let o = common::mechdraw()
        .arg("run")
        .arg(common::root().join("templates").join(template))
        .arg("--out")
        .arg(&out)
        .arg("-q")
        .args(extra)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    (tmp, out)
}

#[test]
fn chain_humienny_2_drawing() {
    let (_tmp, out) = run("chain-humienny-2.toml", &["--set", "stackup.samples=1000"]);
    let svg = std::fs::read_to_string(out.join("chain-humienny-2.svg")).unwrap();
    common::assert_golden_png("chain-humienny-2.png", &svg);
}

#[test]
fn over_dimensioned_chain_drawing_shows_the_reference_dimension() {
    // Matrix (2) plus w9 = 17 from the end of 25: redundant, drawn as "(17)" on REDUNDANT.
    let (_tmp, out) = run(
        "chain-humienny-2.toml",
        &[
            "--set",
            "B=[0, 0, -38, -38, 260, -100, -100, 65, 25]",
            "--set",
            "W=[-38, 25, 80, 260, -100, 55, 65, 15, 17]",
            "--set",
            "stackup.samples=0",
            "--set",
            "name=chain-over",
        ],
    );
    let svg = std::fs::read_to_string(out.join("chain-over.svg")).unwrap();
    assert!(svg.contains("(17)"));
    common::assert_golden_png("chain-over.png", &svg);
}

#[test]
fn chain_humienny_2_dxf_is_audit_clean_and_matches_its_golden_file() {
    let (_tmp, out) = run("chain-humienny-2.toml", &["--set", "stackup.samples=1000"]);
    let dxf = out.join("chain-humienny-2.dxf");
    common::assert_ezdxf_clean(&[&dxf]);
    let text = std::fs::read_to_string(&dxf).unwrap();
    // The dimensions are DIMENSION entities (8 independent, 4 dependent), each block
    // drawing it as the chain does (docs/chain.md): on layer DIMENSIONS the seed's notation,
    // eight base circles and eight arrowheads, one per dimension.
    let text_lf = text.replace("\r\n", "\n");
    assert_eq!(text_lf.matches("\n  0\nDIMENSION\n").count(), 12);
    let count = |entity: &str| {
        text_lf
            .split("\n  0\n")
            .filter(|r| r.starts_with(&format!("{entity}\n")) && r.contains("\n  8\nDIMENSIONS\n"))
            .count()
    };
    assert_eq!(count("CIRCLE"), 8);
    assert_eq!(count("SOLID"), 8);
    common::assert_golden_text("chain-humienny-2.dxf", &text);
}

#[test]
fn chain_humienny_2_z3_histogram() {
    let (_tmp, out) = run("chain-humienny-2.toml", &["--set", "stackup.samples=20000"]);
    let svg = std::fs::read_to_string(out.join("diagrams/chain-humienny-2/Z3-histogram.svg")).unwrap();
    common::assert_golden_png("chain-humienny-2-Z3-histogram.png", &svg);
}
