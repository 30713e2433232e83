//! What a run prints on the terminal (issue 30): the report and warnings, then what it wrote
//! as one line per folder, so that a motion's report does not scroll away behind a line per
//! frame; `--verbose` lists every file, `--quiet` nothing.

mod common;

fn run(extra: &[&str]) -> (String, std::path::PathBuf, tempfile::TempDir) {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let o = common::mechdraw()
        .current_dir(common::root())
        .args(["run", "templates/fourbar-chebyshev.toml", "--set", "phi1_deg.step=10", "--out"])
        .arg(&out)
        .args(extra)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    (String::from_utf8(o.stderr).unwrap(), out, tmp)
}

#[test]
fn a_motion_lists_its_files_per_folder_after_its_report() {
    let (err, out, _tmp) = run(&[]);
    let lines: Vec<&str> = err.lines().collect();
    // The warning, the report (2 lines), the count and a line per folder: ./, diagrams, frames.
    assert!(lines.len() <= 8, "{err}");
    assert!(lines[0].starts_with("warning: transmission angle γ_min = 23.07°"), "{err}");
    assert!(err.contains("fourbar-chebyshev: four-bar, 36 positions solved"), "{err}");
    let listed = format!("wrote 59 files into {}:", out.display());
    let at = lines.iter().position(|l| *l == listed).unwrap_or_else(|| panic!("no `{listed}` in\n{err}"));
    let folders: Vec<&str> = lines[at + 1..].iter().map(|l| l.split_whitespace().next().unwrap()).collect();
    assert_eq!(folders, ["./", "diagrams/fourbar-chebyshev/", "frames/fourbar-chebyshev/"], "{err}");
    assert!(lines[at + 3].ends_with("36 files (.svg; pos_000.svg … pos_350.svg)"), "{err}");
    // What is listed is what is on disk.
    let mut files = Vec::new();
    common::read_tree(&out, std::path::Path::new(""), &mut files);
    assert_eq!(files.len(), 59);
}

#[test]
fn verbose_lists_every_file_and_quiet_nothing() {
    let (err, out, _tmp) = run(&["--verbose"]);
    let wrote: Vec<&str> = err.lines().filter(|l| l.starts_with("wrote ")).collect();
    assert_eq!(wrote.len(), 59, "{err}");
    assert!(wrote.contains(&format!("wrote {}", out.join("frames/fourbar-chebyshev/pos_350.svg").display()).as_str()));
    let (err, _, _tmp) = run(&["--quiet"]);
    assert_eq!(err, "");
}

/// The linkage report's time span as a person writes it (issue 30: fourbar-linkage printed
/// `t = 0..0.3141592653589793 s`, its `to = π/10` in every digit).
#[test]
fn a_linkage_reports_its_time_span_to_six_decimals() {
    let tmp = tempfile::tempdir().unwrap();
    let o = common::mechdraw()
        .current_dir(common::root())
        .args(["run", "templates/fourbar-linkage.toml", "--no-frames", "--out"])
        .arg(tmp.path())
        .output()
        .unwrap();
    let err = String::from_utf8(o.stderr).unwrap();
    assert!(err.contains("361 positions, t = 0..0.314159 s;"), "{err}");
}
