//! `mechdraw diff OLD NEW` (issue 30) as a course's CI runs it on two runs of a template:
//! identical runs pass (exit 0); a coupler 0.1 % longer (`--set l_bc=0.1001`) fails (exit 1)
//! naming the CSV columns and the frames that moved, with diff PNGs; its tables pass with
//! `--tol-rel 2e-2` (at 1e-2 one cell, vM_y at φ1 = 0, moved by 1.04 %: named); a missing
//! directory or a file that cannot be read is bad input (exit 2, the path named).

mod common;

use std::path::Path;
use std::process::Output;

/// The four-bar at every 10° (36 frames), into `dir`, with `set`.
fn run(dir: &Path, set: &[&str]) {
    let mut cmd = common::mechdraw();
    cmd.args(["run", "templates/fourbar-chebyshev.toml", "-q", "--set", "phi1_deg.step=10", "--out"]).arg(dir);
    for s in set {
        cmd.args(["--set", s]);
    }
    let out = cmd.current_dir(common::root()).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
}

fn diff(old: &Path, new: &Path, extra: &[&str], diff_dir: &Path) -> Output {
    common::mechdraw().arg("diff").arg(old).arg(new).arg("--out").arg(diff_dir).args(extra).output().unwrap()
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// The runs every test compares: `old`, the same again, and `l_bc = 0.1001`.
fn runs() -> &'static (tempfile::TempDir, std::path::PathBuf, std::path::PathBuf, std::path::PathBuf) {
    static RUNS: std::sync::OnceLock<(tempfile::TempDir, std::path::PathBuf, std::path::PathBuf, std::path::PathBuf)> =
        std::sync::OnceLock::new();
    RUNS.get_or_init(|| {
        let tmp = tempfile::tempdir().unwrap();
        let (old, same, moved) = (tmp.path().join("old"), tmp.path().join("same"), tmp.path().join("moved"));
        run(&old, &[]);
        run(&same, &[]);
        run(&moved, &["l_bc=0.1001"]);
        (tmp, old, same, moved)
    })
}

#[test]
fn two_identical_runs_are_the_same() {
    let (tmp, old, same, _) = runs();
    let out = diff(old, same, &[], &tmp.path().join("d0"));
    assert_eq!(out.status.code(), Some(0), "{}{}", stdout(&out), String::from_utf8_lossy(&out.stderr));
    let s = stdout(&out);
    assert!(s.contains("0 within tolerance, 0 changed; 0 added, 0 removed"), "{s}");
    assert!(s.trim_end().ends_with("result: the same within the tolerances (exit 0)"), "{s}");
    assert!(!tmp.path().join("d0").exists(), "no diff pictures when nothing changed");
}

#[test]
fn a_longer_rocker_names_the_moved_columns_and_frames_with_diff_pictures() {
    let (tmp, old, _, moved) = runs();
    let d = tmp.path().join("d1");
    let out = diff(old, moved, &[], &d);
    assert_eq!(out.status.code(), Some(1), "{}{}", stdout(&out), String::from_utf8_lossy(&out.stderr));
    let s = stdout(&out);
    // The CSV: B and M move with the rocker, the crank's pin A does not.
    let csv = s.split("  fourbar-chebyshev.csv\n").nth(1).expect("the CSV is listed as changed");
    let csv_lines: Vec<&str> = csv.lines().take_while(|l| l.starts_with("    ")).collect();
    let moved_columns = csv_lines.first().unwrap();
    for col in ["B_x", "B_y", "M_x", "phi3_deg", "omega3", "gamma_deg"] {
        assert!(moved_columns.contains(col), "{col} not named: {moved_columns}");
    }
    for col in ["A_x", "A_y", "phi1_deg"] {
        assert!(
            !moved_columns.split(": ").nth(1).unwrap().split(", ").any(|c| c == col),
            "{col} named: {moved_columns}"
        );
    }
    // The column that moved most for its scale, with its largest difference and where.
    assert!(
        csv_lines.iter().any(|l| l.starts_with("      vM_y: 36 rows of 36; largest |Δ| 0.01 (")
            && l.ends_with("at row 1 (phi1_deg = 0)")),
        "{csv}"
    );
    // The frames: one line for the folder, the frame that moved most, the diff pictures.
    assert!(s.contains("  frames/fourbar-chebyshev/: 36 files (pos_000.svg … pos_350.svg)"), "{s}");
    assert!(s.contains("    most moved: pos_"), "{s}");
    let pngs: Vec<_> = std::fs::read_dir(d.join("frames/fourbar-chebyshev")).unwrap().collect();
    assert_eq!(pngs.len(), 36, "a diff picture per changed frame");
    let picture = resvg::tiny_skia::Pixmap::load_png(d.join("fourbar-chebyshev.svg.diff.png")).unwrap();
    let red = picture.pixels().iter().filter(|p| (p.red(), p.green(), p.blue()) == (255, 0, 0)).count();
    assert!(red > 100, "{red} red pixels in the picture's diff");
    assert!(s.trim_end().ends_with("(exit 1)"), "{s}");
}

/// At 1 %, one cell of the 36 × 96 moved beyond: vM_y at φ1 = 0, where the transmission
/// angle is smallest (γ = 23°) and M is most sensitive to the rocker, moved by 0.0100 m/s,
/// 1.04 % of its column's largest magnitude (0.96 m/s). At 2 % the tables are the same.
#[test]
fn with_a_one_percent_tolerance_only_the_most_sensitive_cell_of_the_tables_moves() {
    let (tmp, old, _, moved) = runs();
    let (a, b) = (tmp.path().join("tables-old"), tmp.path().join("tables-new"));
    for (from, to) in [(old, &a), (moved, &b)] {
        std::fs::create_dir_all(to).unwrap();
        for f in ["fourbar-chebyshev.csv", "fourbar-chebyshev.json"] {
            std::fs::copy(from.join(f), to.join(f)).unwrap();
        }
    }
    let out = diff(&a, &b, &["--tol-rel", "1e-2"], &tmp.path().join("d2"));
    assert_eq!(out.status.code(), Some(1), "{}", stdout(&out));
    let s = stdout(&out);
    assert!(s.contains("    1 of 96 columns moved beyond 1e-2: vM_y\n"), "{s}");
    assert!(
        s.contains("      vM_y: 1 rows of 36; largest |Δ| 0.01 (0.0104 of its scale 0.9599) at row 1 (phi1_deg = 0)"),
        "{s}"
    );
    assert!(s.contains("      positions[].vM[1]: 1 values; "), "{s}");
    let out = diff(&a, &b, &["--tol-rel", "2e-2"], &tmp.path().join("d3"));
    assert_eq!(out.status.code(), Some(0), "{}", stdout(&out));
    assert!(
        stdout(&out).contains("  fourbar-chebyshev.csv\n    every cell within 2e-2 (bytes differ)"),
        "{}",
        stdout(&out)
    );
    // And the default tolerance flags 72 of the 96 columns.
    let out = diff(&a, &b, &[], &tmp.path().join("d4"));
    assert_eq!(out.status.code(), Some(1));
    assert!(stdout(&out).contains("72 of 96 columns moved beyond 1e-9: "), "{}", stdout(&out));
}

#[test]
fn a_missing_directory_or_an_unreadable_file_is_bad_input() {
    let (tmp, old, _, _) = runs();
    let missing = tmp.path().join("no-such-run");
    let out = diff(old, &missing, &[], &tmp.path().join("d5"));
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(
        err.trim_end(),
        format!(
            "error: {}: no such directory (mechdraw diff compares two output directories: OLD_DIR NEW_DIR)",
            missing.display()
        )
    );
    // A JSON cut short.
    let (a, b) = (tmp.path().join("bad-old"), tmp.path().join("bad-new"));
    std::fs::create_dir_all(&a).unwrap();
    std::fs::create_dir_all(&b).unwrap();
    std::fs::write(a.join("x.json"), "{\"a\": 1}").unwrap();
    std::fs::write(b.join("x.json"), "{\"a\": ").unwrap();
    let out = diff(&a, &b, &[], &tmp.path().join("d6"));
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.starts_with(&format!("error: {}: cannot read it as JSON: ", b.join("x.json").display())), "{err}");
    // A tolerance that is not one.
    let out = diff(&a, &a, &["--tol-rel=-1"], &tmp.path().join("d7"));
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("`-1` is not a tolerance"));
}

#[test]
fn added_and_removed_files_fail() {
    let (tmp, old, same, _) = runs();
    let b = tmp.path().join("plus");
    std::fs::create_dir_all(b.join("frames")).unwrap();
    for e in std::fs::read_dir(same).unwrap() {
        let e = e.unwrap();
        if e.path().is_file() && !e.file_name().to_string_lossy().ends_with(".dxf") {
            std::fs::copy(e.path(), b.join(e.file_name())).unwrap();
        }
    }
    std::fs::write(b.join("extra.txt"), "x").unwrap();
    let out = diff(old, &b, &[], &tmp.path().join("d8"));
    assert_eq!(out.status.code(), Some(1));
    let s = stdout(&out);
    assert!(s.contains("added (only in the new directory): 1\n  extra.txt"), "{s}");
    assert!(s.contains("removed (only in the old directory): "), "{s}");
    assert!(s.contains("fourbar-chebyshev.dxf"), "{s}");
    assert!(s.contains("  frames/fourbar-chebyshev/: 36 files (pos_000.svg … pos_350.svg)"), "{s}");
}
