//! Golden files of the triad template: the seed's Fig. 3 (golden/triad-popa.png, the SVG
//! rasterised, and golden/triad-popa.dxf, audited with ezdxf) and the sheet of every
//! assembly mode (golden/triad-popa-modes.png and golden/triad-popa-modes.dxf). Re-bless with UPDATE_GOLDEN=1
//! and look at the result (golden/README.md).

mod common;

use std::path::Path;

fn run_template(out: &Path) {
    let status = common::mechdraw()
        .args(["run", "templates/triad-popa.toml", "--quiet", "--out"])
        .arg(out)
        .current_dir(common::root())
        .status()
        .unwrap();
    assert!(status.success());
}

#[test]
fn triad_popa_svg_matches_golden_png() {
    let tmp = tempfile::tempdir().unwrap();
    run_template(tmp.path());
    let svg = std::fs::read_to_string(tmp.path().join("triad-popa.svg")).unwrap();
    common::assert_golden_png("triad-popa.png", &svg);
}

#[test]
fn triad_popa_dxf_matches_golden_and_audits_clean() {
    let tmp = tempfile::tempdir().unwrap();
    run_template(tmp.path());
    let path = tmp.path().join("triad-popa.dxf");
    let text = std::fs::read_to_string(&path).unwrap();
    common::assert_golden_text("triad-popa.dxf", &text);
    common::assert_ezdxf_clean(&[&path]);
}

#[test]
fn triad_popa_modes_svg_matches_golden_png() {
    let tmp = tempfile::tempdir().unwrap();
    run_template(tmp.path());
    let svg = std::fs::read_to_string(tmp.path().join("triad-popa-modes.svg")).unwrap();
    common::assert_golden_png("triad-popa-modes.png", &svg);
}

#[test]
fn triad_popa_modes_dxf_matches_golden_and_audits_clean() {
    let tmp = tempfile::tempdir().unwrap();
    run_template(tmp.path());
    let path = tmp.path().join("triad-popa-modes.dxf");
    let text = std::fs::read_to_string(&path).unwrap();
    common::assert_golden_text("triad-popa-modes.dxf", &text);
    common::assert_ezdxf_clean(&[&path]);
}
