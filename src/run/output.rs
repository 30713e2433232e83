//! All-or-nothing output: files are written into a staging directory inside the output
//! directory and moved into place only when every one of them has been written. A run
//! that fails leaves the output directory as it was.

use std::path::{Path, PathBuf};

use crate::Error;

/// Outputs of one run, staged until [`Output::commit`].
#[derive(Debug)]
pub struct Output {
    dir: PathBuf,
    staging: PathBuf,
    files: Vec<PathBuf>,
    committed: bool,
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> Error + '_ {
    move |source| Error::Io { path: path.display().to_string(), source }
}

impl Output {
    /// Prepares to write into `dir` (created if missing).
    pub fn new(dir: &Path) -> Result<Output, Error> {
        std::fs::create_dir_all(dir).map_err(io(dir))?;
        let staging = dir.join(format!(".mechdraw-partial-{}", std::process::id()));
        if staging.exists() {
            std::fs::remove_dir_all(&staging).map_err(io(&staging))?;
        }
        std::fs::create_dir_all(&staging).map_err(io(&staging))?;
        Ok(Output { dir: dir.to_path_buf(), staging, files: Vec::new(), committed: false })
    }

    /// The final output directory.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Stages `bytes` as `rel` (a path relative to the output directory, e.g.
    /// `frames/pos_000.svg`).
    pub fn write(&mut self, rel: impl AsRef<Path>, bytes: impl AsRef<[u8]>) -> Result<(), Error> {
        let rel = rel.as_ref();
        let path = self.staging.join(rel);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).map_err(io(parent))?;
        }
        std::fs::write(&path, bytes).map_err(io(&path))?;
        self.files.push(rel.to_path_buf());
        Ok(())
    }

    /// Writes `files` (`(rel, bytes)` as for [`Output::write`]) into the staging directory
    /// through a shared reference, so that a batch (the frames of an animation) can be staged
    /// on one thread while the run builds its other outputs on another. They are listed with
    /// [`Output::record_paths`] (staged files never listed are still moved at commit).
    ///
    /// The files are written one after another: they go into one directory, whose lock
    /// serialises file creation anyway, and parallel writers only spin on it.
    fn stage(&self, files: &[super::bytes::File<'_>]) -> Result<(), Error> {
        let mut dirs: Vec<PathBuf> =
            files.iter().filter_map(|(rel, _)| self.staging.join(rel).parent().map(Path::to_path_buf)).collect();
        dirs.sort();
        dirs.dedup();
        for d in &dirs {
            std::fs::create_dir_all(d).map_err(io(d))?;
        }
        for (rel, pieces) in files {
            let path = self.staging.join(rel);
            write_pieces(&path, pieces).map_err(io(&path))?;
        }
        Ok(())
    }

    /// Stages as `rel` (as for [`Output::write`]) the file made of `pieces` one after the
    /// other, without joining them in memory first (the live page: a few kilobytes of its
    /// own around the 10 MB module, which is written straight from the program's image).
    pub fn write_pieces(&mut self, rel: impl AsRef<Path>, pieces: &[&[u8]]) -> Result<(), Error> {
        let rel = rel.as_ref();
        let path = self.staging.join(rel);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).map_err(io(parent))?;
        }
        write_pieces(&path, pieces).map_err(io(&path))?;
        self.files.push(rel.to_path_buf());
        Ok(())
    }

    /// Lists files already staged (through [`super::bytes::Sink::put`]) among the run's
    /// files, in this order.
    pub fn record_paths(&mut self, rels: impl IntoIterator<Item = PathBuf>) {
        self.files.extend(rels);
    }

    /// Moves every staged file into the output directory. Directories are merged, except a
    /// staged directory that holds only files (e.g. `frames/<name>/`): it replaces the old
    /// one whole, so no stale frames of an earlier run remain while other scenes' outputs in
    /// the same directory are kept. Returns the final paths in the order they were written.
    pub fn commit(mut self) -> Result<Vec<PathBuf>, Error> {
        move_tree(&self.staging, &self.dir)?;
        std::fs::remove_dir_all(&self.staging).map_err(io(&self.staging))?;
        self.committed = true;
        Ok(self.files.iter().map(|f| self.dir.join(f)).collect())
    }
}

/// Creates (or truncates) the file `path` and writes `pieces` into it one after the other,
/// as few system calls as the kernel takes them in (one for a frame's two pieces).
fn write_pieces(path: &Path, pieces: &[&[u8]]) -> std::io::Result<()> {
    use std::io::{IoSlice, Write};
    let mut file = std::fs::File::create(path)?;
    let mut slices: Vec<IoSlice<'_>> = pieces.iter().filter(|p| !p.is_empty()).map(|p| IoSlice::new(p)).collect();
    let mut rest = &mut slices[..];
    while !rest.is_empty() {
        match file.write_vectored(rest) {
            Ok(0) => return Err(std::io::ErrorKind::WriteZero.into()),
            Ok(n) => IoSlice::advance_slices(&mut rest, n),
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
    Ok(())
}

/// Moves the entries of `from` into `to` (see [`Output::commit`] for the rule).
fn move_tree(from: &Path, to: &Path) -> Result<(), Error> {
    let entries = std::fs::read_dir(from).map_err(io(from))?;
    for entry in entries {
        let entry = entry.map_err(io(from))?;
        let source = entry.path();
        let target = to.join(entry.file_name());
        if source.is_dir() {
            let has_subdir =
                std::fs::read_dir(&source).map_err(io(&source))?.any(|e| e.is_ok_and(|e| e.path().is_dir()));
            if has_subdir && target.is_dir() {
                move_tree(&source, &target)?;
                continue;
            }
            if target.is_dir() {
                std::fs::remove_dir_all(&target).map_err(io(&target))?;
            }
        }
        std::fs::rename(&source, &target).map_err(io(&target))?;
    }
    Ok(())
}

impl super::bytes::Sink for Output {
    fn put(&self, files: &[super::bytes::File<'_>]) -> Result<(), Error> {
        // Listed by the caller, in the canonical order (see `record_paths`).
        self.stage(files)
    }
}

impl Drop for Output {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_dir_all(&self.staging);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nothing_lands_until_commit_and_a_dropped_output_leaves_no_trace() {
        let tmp = tempfile::tempdir().unwrap();
        {
            let mut out = Output::new(tmp.path()).unwrap();
            out.write("a.txt", "x").unwrap();
            assert!(!tmp.path().join("a.txt").exists());
        }
        assert_eq!(std::fs::read_dir(tmp.path()).unwrap().count(), 0);
        let mut out = Output::new(tmp.path()).unwrap();
        out.write("frames/f1.svg", "y").unwrap();
        out.write("a.txt", "x").unwrap();
        let files = out.commit().unwrap();
        assert_eq!(files.len(), 2);
        assert_eq!(std::fs::read_to_string(tmp.path().join("frames/f1.svg")).unwrap(), "y");
        assert_eq!(std::fs::read_dir(tmp.path()).unwrap().count(), 2);
    }

    #[test]
    fn many_files_are_staged_in_order_and_land_at_commit() {
        let tmp = tempfile::tempdir().unwrap();
        let mut out = Output::new(tmp.path()).unwrap();
        let files: Vec<(String, Vec<u8>)> =
            (0..50).map(|i| (format!("frames/f{i:02}.svg"), format!("{i}").into_bytes())).collect();
        let views: Vec<super::super::bytes::File<'_>> =
            files.iter().map(|(n, b)| (n.clone(), vec![&b[..1], &b[1..]])).collect();
        super::super::bytes::Sink::put(&out, &views).unwrap();
        out.record_paths(files.iter().map(|(n, _)| PathBuf::from(n)));
        assert!(!tmp.path().join("frames").exists());
        let written = out.commit().unwrap();
        assert_eq!(written.len(), 50);
        assert_eq!(written[7], tmp.path().join("frames/f07.svg"));
        assert_eq!(std::fs::read_to_string(tmp.path().join("frames/f49.svg")).unwrap(), "49");
    }

    #[test]
    fn a_file_in_pieces_is_the_pieces_one_after_the_other() {
        let tmp = tempfile::tempdir().unwrap();
        let mut out = Output::new(tmp.path()).unwrap();
        let big: Vec<u8> = (0..3_000_000u32).map(|i| (i % 251) as u8).collect();
        let pieces: [&[u8]; 5] = [b"head ", &[], &big, b"", b" tail"];
        out.write_pieces("p/page.html", &pieces).unwrap();
        out.write_pieces("empty", &[]).unwrap();
        out.commit().unwrap();
        assert!(std::fs::read(tmp.path().join("p/page.html")).unwrap() == pieces.concat());
        assert_eq!(std::fs::read(tmp.path().join("empty")).unwrap().len(), 0);
    }

    #[test]
    fn leaf_directories_are_replaced_and_others_merged() {
        let tmp = tempfile::tempdir().unwrap();
        let mut out = Output::new(tmp.path()).unwrap();
        out.write("frames/a/pos_000.svg", "a0").unwrap();
        out.write("frames/a/pos_001.svg", "a1").unwrap();
        out.write("frames/b/pos_000.svg", "b0").unwrap();
        out.commit().unwrap();
        // A second run of scene `a` with fewer frames: a's stale frame goes, b's frames stay.
        let mut out = Output::new(tmp.path()).unwrap();
        out.write("frames/a/pos_000.svg", "a0'").unwrap();
        out.commit().unwrap();
        assert_eq!(std::fs::read_to_string(tmp.path().join("frames/a/pos_000.svg")).unwrap(), "a0'");
        assert!(!tmp.path().join("frames/a/pos_001.svg").exists());
        assert_eq!(std::fs::read_to_string(tmp.path().join("frames/b/pos_000.svg")).unwrap(), "b0");
    }
}
