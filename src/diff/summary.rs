//! The report as a CI log shows it: one line of counts, the added and removed files, what
//! changed (a folder with many changed files — a motion's frames — as one line: how many,
//! which, the one that moved most), what moved within the tolerances, then the verdict.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use super::{FileDiff, Report, Verdict};

/// Files listed one by one in a folder; more are summarised as one line.
const LISTED_PER_FOLDER: usize = 3;

/// Names listed for added or removed files; more are counted.
const LISTED_NAMES: usize = 10;

pub(super) fn text(r: &Report) -> String {
    let mut s = String::new();
    let count = |v: Verdict| r.files.iter().filter(|f| f.verdict == v).count();
    let _ = writeln!(
        s,
        "mechdraw diff {} {} (tol-rel {:e}, tol-px {})",
        r.old.display(),
        r.new.display(),
        r.tol_rel,
        r.tol_px
    );
    let _ = writeln!(
        s,
        "{} files compared: {} identical, {} within tolerance, {} changed; {} added, {} removed",
        r.files.len(),
        count(Verdict::Same),
        count(Verdict::Within),
        count(Verdict::Changed),
        r.added.len(),
        r.removed.len()
    );
    names(&mut s, "added (only in the new directory)", &r.added);
    names(&mut s, "removed (only in the old directory)", &r.removed);
    section(&mut s, "changed beyond the tolerances:", r, Verdict::Changed);
    section(&mut s, "within the tolerances (bytes differ):", r, Verdict::Within);
    let _ = if r.passed() {
        writeln!(s, "result: the same within the tolerances (exit 0)")
    } else {
        writeln!(
            s,
            "result: DIFFERENT: {} changed, {} added, {} removed (exit 1)",
            count(Verdict::Changed),
            r.added.len(),
            r.removed.len()
        )
    };
    s
}

fn names(s: &mut String, title: &str, list: &[String]) {
    if list.is_empty() {
        return;
    }
    let _ = writeln!(s, "{title}: {}", list.len());
    for (folder, files) in by_folder(list.iter().map(String::as_str)) {
        if !folder.is_empty() && files.len() > LISTED_PER_FOLDER {
            let _ = writeln!(s, "  {folder}: {} files ({} … {})", files.len(), files[0], files[files.len() - 1]);
        } else {
            for f in files.iter().take(LISTED_NAMES) {
                let _ = writeln!(s, "  {folder}{f}");
            }
        }
    }
}

/// `dir/sub/file` → (`dir/sub/`, [`file`, …]), folders in order.
fn by_folder<'a>(paths: impl Iterator<Item = &'a str>) -> BTreeMap<&'a str, Vec<&'a str>> {
    let mut m: BTreeMap<&str, Vec<&str>> = BTreeMap::new();
    for p in paths {
        let (folder, file) = p.rfind('/').map_or(("", p), |i| (&p[..=i], &p[i + 1..]));
        m.entry(folder).or_default().push(file);
    }
    m
}

fn section(s: &mut String, title: &str, r: &Report, verdict: Verdict) {
    let files: Vec<&FileDiff> = r.files.iter().filter(|f| f.verdict == verdict).collect();
    if files.is_empty() {
        return;
    }
    let _ = writeln!(s, "{title}");
    let mut folders: BTreeMap<&str, Vec<&FileDiff>> = BTreeMap::new();
    for f in &files {
        let folder = f.path.rfind('/').map_or("", |i| &f.path[..=i]);
        folders.entry(folder).or_default().push(f);
    }
    for (folder, fs) in folders {
        // The run's own files (the top folder) one by one; a folder of frames, diagrams or
        // printed pages as one line.
        if !folder.is_empty() && fs.len() > LISTED_PER_FOLDER {
            group(s, folder, &fs);
        } else {
            for f in fs {
                let _ = writeln!(s, "  {}", f.path);
                for d in &f.details {
                    let _ = writeln!(s, "    {d}");
                }
            }
        }
    }
}

/// Many files of one folder (a motion's frames): how many, the first and last, the one with
/// the most pixels moved, and where the diff pictures are.
fn group(s: &mut String, folder: &str, fs: &[&FileDiff]) {
    let name = |f: &FileDiff| f.path[folder.len()..].to_string();
    let _ = writeln!(s, "  {folder}: {} files ({} … {})", fs.len(), name(fs[0]), name(fs[fs.len() - 1]));
    if let Some(worst) = fs.iter().filter(|f| f.pixels > 0).max_by_key(|f| f.pixels) {
        let _ = writeln!(s, "    most moved: {}: {}", name(worst), worst.details.first().map_or("", String::as_str));
        if let Some(dir) = worst.diff_png.as_ref().and_then(|p| p.parent()) {
            let _ = writeln!(s, "    diff pictures: {}/*.diff.png", dir.display());
        }
    } else if let Some(first) = fs[0].details.first() {
        let _ = writeln!(s, "    {}: {first}", name(fs[0]));
    }
}
