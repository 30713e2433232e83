//! What a run wrote, as the terminal shows it: a line per folder with its count (a motion's
//! 360 frames are one line, so the report above stays on the screen), the names where a
//! folder holds a few files; `--verbose` lists every file.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Files named one by one in a folder's line; a folder with more is counted by extension.
pub const NAMED_PER_FOLDER: usize = 12;

/// The summary of `written` (paths inside `dir`, as [`super::Outcome::written`] has them):
/// `wrote N files into DIR:` and one line per folder. With `verbose`, one `wrote PATH` line
/// per file instead (what the command line printed before).
pub fn summary(dir: &Path, written: &[PathBuf], verbose: bool) -> String {
    if verbose {
        return written.iter().map(|f| format!("wrote {}\n", f.display())).collect();
    }
    if written.is_empty() {
        return String::new();
    }
    let mut folders: BTreeMap<PathBuf, Vec<String>> = BTreeMap::new();
    for f in written {
        let rel = f.strip_prefix(dir).unwrap_or(f);
        let folder = rel.parent().map(Path::to_path_buf).unwrap_or_default();
        folders
            .entry(folder)
            .or_default()
            .push(rel.file_name().map_or_else(String::new, |n| n.to_string_lossy().into_owned()));
    }
    let mut s = format!("wrote {} files into {}", written.len(), dir.display());
    s.push_str(if folders.len() > 1 || written.len() > NAMED_PER_FOLDER { ":\n" } else { ": " });
    if folders.len() == 1 && written.len() <= NAMED_PER_FOLDER {
        let _ = writeln!(s, "{}", folders.values().next().map(|v| v.join(", ")).unwrap_or_default());
        return s;
    }
    let width = folders.keys().map(|k| shown(k).chars().count()).max().unwrap_or(0);
    for (folder, names) in &folders {
        let _ = writeln!(s, "  {:<width$}  {}", shown(folder), describe(names));
    }
    s
}

/// A folder relative to the output directory, as listed: `./` for the directory itself.
fn shown(folder: &Path) -> String {
    if folder.as_os_str().is_empty() { "./".to_string() } else { format!("{}/", folder.display()) }
}

/// `3 files: a.dxf, a.svg, a.json` or `360 files (.svg)`.
fn describe(names: &[String]) -> String {
    let n = names.len();
    let noun = if n == 1 { "file" } else { "files" };
    if n <= NAMED_PER_FOLDER {
        return format!("{n} {noun}: {}", names.join(", "));
    }
    let mut by_ext: BTreeMap<&str, usize> = BTreeMap::new();
    for name in names {
        *by_ext.entry(name.rfind('.').map_or("", |i| &name[i..])).or_insert(0) += 1;
    }
    let exts: Vec<String> =
        by_ext.iter().map(|(e, c)| if by_ext.len() == 1 { e.to_string() } else { format!("{c} {e}") }).collect();
    format!("{n} {noun} ({}; {} … {})", exts.join(", "), names[0], names[n - 1])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_are_one_line_and_the_top_folder_is_named() {
        let dir = Path::new("out");
        let mut files: Vec<PathBuf> =
            ["fourbar.dxf", "fourbar.svg", "fourbar.csv", "fourbar.json"].iter().map(|f| dir.join(f)).collect();
        files.extend((0..360).map(|k| dir.join(format!("frames/fourbar/pos_{k:03}.svg"))));
        files.push(dir.join("diagrams/fourbar/gamma.svg"));
        let s = summary(dir, &files, false);
        assert_eq!(s.lines().count(), 4, "{s}");
        assert_eq!(s.lines().next().unwrap(), "wrote 365 files into out:");
        let line = |folder: &str, rest: &str| {
            s.lines().any(|l| l.trim_start().starts_with(folder) && l.trim_end().ends_with(rest))
        };
        assert!(line("./", "  4 files: fourbar.dxf, fourbar.svg, fourbar.csv, fourbar.json"), "{s}");
        assert!(line("frames/fourbar/", "  360 files (.svg; pos_000.svg … pos_359.svg)"), "{s}");
        assert!(line("diagrams/fourbar/", "  1 file: gamma.svg"), "{s}");
        assert_eq!(summary(dir, &files, true).lines().count(), 365);
        assert_eq!(summary(dir, &files, true).lines().nth(4).unwrap(), "wrote out/frames/fourbar/pos_000.svg");
    }

    #[test]
    fn a_few_files_in_one_folder_are_one_line() {
        let dir = Path::new("o");
        let files = vec![dir.join("t.dxf"), dir.join("t.svg")];
        assert_eq!(summary(dir, &files, false), "wrote 2 files into o: t.dxf, t.svg\n");
        assert_eq!(summary(dir, &[], false), "");
    }
}
