//! All-or-nothing output: files are written into a staging directory inside the output
//! directory and moved into place only when every one of them has been written. A run
//! that fails — an error, SIGINT, SIGTERM or SIGHUP, a commit that cannot finish — leaves
//! the output directory as it was.
//!
//! - Staging: `DIR/.mechdraw-partial-<pid>-<n>/`, holding `new/` (the run's files), `old/`
//!   (what the commit replaces, kept until it has finished) and `lock`, a file the live
//!   run holds an advisory lock on (`flock`, on Unix). A later run removes the staging
//!   directories whose lock it can take (their run has died: the system released the
//!   lock), and those without a lock file older than [`STALE_WITHOUT_LOCK`]. Elsewhere than
//!   on Unix there is no lock, and a staging directory is stale by its age alone.
//! - Signals ([`remove_staging_on_signals`], the command line installs it): the handler
//!   waits for the files being written and any commit in progress (which then rolls back),
//!   removes every staging directory of the process and exits with 128 + the signal's
//!   number (130 for SIGINT, 143 for SIGTERM, 129 for SIGHUP).
//! - Commit ([`Output::commit`]): first checks that nothing of another type is in the way
//!   (a directory where a file goes, or a file where a directory goes), then moves each
//!   replaced entry into `old/` and the new one into place, one rename each, keeping a
//!   journal; on any failure (or a signal meanwhile) it undoes the journal in reverse, so
//!   DIR is as it was. Only a process killed outright (SIGKILL, power loss) in the middle
//!   of a commit can leave a mix; the old files are then in the stale staging's `old/`
//!   until the next run removes it.
//!
//! Every path written goes through `Output::target`: a path relative to the staging
//! directory made only of plain parts (no root, prefix, `.`, `..` or empty part), the
//! second line of defence behind [`super::paths::RelPath`].

use std::fs::{self, File};
use std::path::{Component, Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Mutex, RwLock};
use std::time::Duration;

use crate::Error;

/// Prefix of the staging directories' names inside the output directory.
pub const STAGING_PREFIX: &str = ".mechdraw-partial-";

/// A staging directory with no lock file (its run died between creating it and its lock,
/// or an older mechdraw made it) is removed by a later run when it is older than this.
pub const STALE_WITHOUT_LOCK: Duration = Duration::from_secs(600);

/// Staging directories of this process's live outputs (the signal handler removes them).
static LIVE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());
/// Held shared while files are staged or a commit runs; the signal handler takes it
/// exclusively, so that it removes a staging directory no writer is filling and that no
/// commit is moving.
static GATE: RwLock<()> = RwLock::new(());
/// Set by the signal handler before it waits for the gate: a commit in progress rolls back.
static INTERRUPTED: AtomicBool = AtomicBool::new(false);
/// Numbers the staging directories of one process.
static SEQUENCE: AtomicUsize = AtomicUsize::new(0);

/// Outputs of one run, staged until [`Output::commit`].
#[derive(Debug)]
pub struct Output {
    dir: PathBuf,
    staging: PathBuf,
    /// `staging/new`: the run's files, laid out as they will be in `dir`.
    new: PathBuf,
    /// The lock on `staging/lock`, held while this output lives.
    _lock: File,
    files: Vec<PathBuf>,
    committed: bool,
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> Error + '_ {
    move |source| Error::Io { path: path.display().to_string(), source }
}

/// The shared side of [`GATE`] (a poisoned gate is still a gate).
fn shared() -> std::sync::RwLockReadGuard<'static, ()> {
    GATE.read().unwrap_or_else(std::sync::PoisonError::into_inner)
}

fn live() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    LIVE.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

impl Output {
    /// Prepares to write into `dir` (created if missing), removing the staging directories
    /// that dead runs left there.
    pub fn new(dir: &Path) -> Result<Output, Error> {
        let _gate = shared();
        fs::create_dir_all(dir).map_err(io(dir))?;
        remove_stale(dir);
        let n = SEQUENCE.fetch_add(1, Ordering::Relaxed);
        let staging = dir.join(format!("{STAGING_PREFIX}{}-{n}", std::process::id()));
        live().push(staging.clone());
        let made = (|| {
            if staging.exists() {
                fs::remove_dir_all(&staging).map_err(io(&staging))?;
            }
            fs::create_dir_all(&staging).map_err(io(&staging))?;
            let lock_path = staging.join("lock");
            let lock = File::create(&lock_path).map_err(io(&lock_path))?;
            if !try_lock(&lock) {
                return Err(Error::Io {
                    path: lock_path.display().to_string(),
                    source: std::io::Error::other("cannot lock the staging directory"),
                });
            }
            let new = staging.join("new");
            fs::create_dir(&new).map_err(io(&new))?;
            Ok((lock, new))
        })();
        match made {
            Ok((lock, new)) => {
                Ok(Output { dir: dir.to_path_buf(), staging, new, _lock: lock, files: Vec::new(), committed: false })
            }
            Err(e) => {
                let _ = fs::remove_dir_all(&staging);
                live().retain(|p| p != &staging);
                Err(e)
            }
        }
    }

    /// The final output directory.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Where `rel` is staged: inside `new/`, or an error when `rel` is not a plain relative
    /// path (a root, a prefix, `.`, `..` or an empty part: compared by component).
    fn target(&self, rel: &Path) -> Result<PathBuf, Error> {
        let mut parts = 0;
        for c in rel.components() {
            match c {
                Component::Normal(p) if !p.is_empty() => parts += 1,
                _ => {
                    return Err(Error::OutputPath {
                        path: crate::text::excerpt(&rel.display().to_string()),
                        message: "it is not a plain path inside the output directory".into(),
                    });
                }
            }
        }
        // The components hide an empty part (`a//b`, `a/`) and a `.` inside (`a/./b`).
        let text = rel.as_os_str().to_string_lossy();
        if parts == 0 || text.split(['/', std::path::MAIN_SEPARATOR]).any(|p| p.is_empty() || p == ".") {
            return Err(Error::OutputPath {
                path: crate::text::excerpt(&text),
                message: "it has an empty part or a `.`".into(),
            });
        }
        Ok(self.new.join(rel))
    }

    /// Stages `bytes` as `rel` (a path relative to the output directory, e.g.
    /// `frames/pos_000.svg`).
    pub fn write(&mut self, rel: impl AsRef<Path>, bytes: impl AsRef<[u8]>) -> Result<(), Error> {
        self.write_pieces(rel, &[bytes.as_ref()])
    }

    /// Writes `files` (`(rel, bytes)` as for [`Output::write`]) into the staging directory
    /// through a shared reference, so that a batch (the frames of an animation) can be staged
    /// on one thread while the run builds its other outputs on another. They are listed with
    /// [`Output::record_paths`] (staged files never listed are still moved at commit).
    ///
    /// The files are written one after another: they go into one directory, whose lock
    /// serialises file creation anyway, and parallel writers only spin on it.
    fn stage(&self, files: &[super::bytes::File<'_>]) -> Result<(), Error> {
        let targets: Vec<PathBuf> =
            files.iter().map(|(rel, _)| self.target(Path::new(rel.as_str()))).collect::<Result<_, _>>()?;
        let _gate = shared();
        let mut dirs: Vec<&Path> = targets.iter().filter_map(|t| t.parent()).collect();
        dirs.sort();
        dirs.dedup();
        for d in dirs {
            fs::create_dir_all(d).map_err(io(d))?;
        }
        for (path, (_, pieces)) in targets.iter().zip(files) {
            write_pieces(path, pieces).map_err(io(path))?;
        }
        Ok(())
    }

    /// Stages as `rel` (as for [`Output::write`]) the file made of `pieces` one after the
    /// other, without joining them in memory first (the live page: a few kilobytes of its
    /// own around the 10 MB module, which is written straight from the program's image).
    pub fn write_pieces(&mut self, rel: impl AsRef<Path>, pieces: &[&[u8]]) -> Result<(), Error> {
        let rel = rel.as_ref();
        let path = self.target(rel)?;
        let _gate = shared();
        if let Some(parent) = path.parent() {
            fs::create_dir_all(parent).map_err(io(parent))?;
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
    ///
    /// All or nothing: when something of another type is in the way, when a move fails or
    /// when a signal arrives meanwhile, every move already made is undone and the output
    /// directory is as it was.
    pub fn commit(self) -> Result<Vec<PathBuf>, Error> {
        self.commit_with(&mut |_| Ok(()))
    }

    /// [`Output::commit`] with `before` called before each move (a test fails one there).
    fn commit_with(mut self, before: &mut dyn FnMut(&Path) -> std::io::Result<()>) -> Result<Vec<PathBuf>, Error> {
        let _gate = shared();
        in_the_way(&self.new, &self.dir)?;
        let old = self.staging.join("old");
        fs::create_dir(&old).map_err(io(&old))?;
        let mut journal = Journal { old, steps: Vec::new(), before };
        let moved = journal.place(&self.new, &self.dir);
        let moved = match moved {
            Ok(()) if INTERRUPTED.load(Ordering::SeqCst) => Err(Error::Io {
                path: self.dir.display().to_string(),
                source: std::io::Error::new(std::io::ErrorKind::Interrupted, "interrupted by a signal"),
            }),
            other => other,
        };
        if let Err(e) = moved {
            journal.undo();
            return Err(e);
        }
        self.committed = true;
        // What the commit replaced goes with the staging directory (a later run removes what
        // this cannot).
        let _ = fs::remove_dir_all(&self.staging);
        Ok(self.files.iter().map(|f| self.dir.join(f)).collect())
    }
}

/// Removes the staging directories in `dir` whose run has died (see the module's docs);
/// what cannot be removed stays, silently (it may be another user's).
fn remove_stale(dir: &Path) {
    let Ok(entries) = fs::read_dir(dir) else { return };
    for entry in entries.flatten() {
        if !entry.file_name().to_string_lossy().starts_with(STAGING_PREFIX) {
            continue;
        }
        let path = entry.path();
        if !fs::symlink_metadata(&path).is_ok_and(|m| m.is_dir()) {
            continue;
        }
        let dead = match File::open(path.join("lock")) {
            // The lock taken: no live run holds it. It is released when `lock` is dropped,
            // after the directory is gone.
            Ok(lock) if cfg!(unix) => try_lock(&lock),
            _ => entry
                .metadata()
                .and_then(|m| m.modified())
                .is_ok_and(|t| t.elapsed().is_ok_and(|age| age > STALE_WITHOUT_LOCK)),
        };
        if dead {
            let _ = fs::remove_dir_all(&path);
        }
    }
}

/// Takes the exclusive advisory lock on `file` without waiting; whether it was free.
#[cfg(unix)]
fn try_lock(file: &File) -> bool {
    rustix::fs::flock(file, rustix::fs::FlockOperation::NonBlockingLockExclusive).is_ok()
}

/// No advisory locks here: every staging directory counts as held (stale by age alone).
#[cfg(not(unix))]
fn try_lock(_: &File) -> bool {
    true
}

/// The kind of an entry, symbolic links not followed (a link is replaced, never entered).
fn is_real_dir(p: &Path) -> bool {
    fs::symlink_metadata(p).is_ok_and(|m| m.is_dir())
}

/// Whether a staged directory holds another directory (then it is merged into the old one).
fn has_subdir(dir: &Path) -> Result<bool, Error> {
    Ok(fs::read_dir(dir).map_err(io(dir))?.any(|e| e.is_ok_and(|e| is_real_dir(&e.path()))))
}

/// Refuses a commit of `from` into `to` that would replace a directory with a file or a
/// file with a directory that it would merge into: the user's, most likely, not ours.
fn in_the_way(from: &Path, to: &Path) -> Result<(), Error> {
    for entry in fs::read_dir(from).map_err(io(from))? {
        let entry = entry.map_err(io(from))?;
        let (source, target) = (entry.path(), to.join(entry.file_name()));
        let Ok(meta) = fs::symlink_metadata(&target) else { continue };
        let conflict = if is_real_dir(&source) { !meta.is_dir() && !meta.is_symlink() } else { meta.is_dir() };
        if conflict {
            let what = if meta.is_dir() { "a directory" } else { "a file" };
            return Err(Error::Io {
                path: target.display().to_string(),
                source: std::io::Error::new(
                    std::io::ErrorKind::AlreadyExists,
                    format!("{what} is in the way (nothing was written: move it or choose another --out)"),
                ),
            });
        }
        if is_real_dir(&source) && meta.is_dir() && has_subdir(&source)? {
            in_the_way(&source, &target)?;
        }
    }
    Ok(())
}

/// One move of a commit, undone in reverse order on failure.
#[derive(Debug)]
enum Step {
    /// An old entry moved from `target` to `kept` (inside `old/`).
    Aside { target: PathBuf, kept: PathBuf },
    /// A staged entry moved from `source` to `target`.
    Placed { source: PathBuf, target: PathBuf },
}

/// The moves of a commit so far.
struct Journal<'a> {
    old: PathBuf,
    steps: Vec<Step>,
    before: &'a mut dyn FnMut(&Path) -> std::io::Result<()>,
}

impl Journal<'_> {
    fn rename(&mut self, from: &Path, to: &Path) -> Result<(), Error> {
        (self.before)(to).and_then(|()| fs::rename(from, to)).map_err(io(to))
    }

    /// Moves the entries of `from` into `to` (see [`Output::commit`] for the rule).
    fn place(&mut self, from: &Path, to: &Path) -> Result<(), Error> {
        // Listed first: the directory changes as its entries move out.
        let entries = fs::read_dir(from).map_err(io(from))?.collect::<Result<Vec<_>, _>>().map_err(io(from))?;
        for entry in entries {
            let (source, target) = (entry.path(), to.join(entry.file_name()));
            let exists = fs::symlink_metadata(&target).is_ok();
            if exists && is_real_dir(&source) && is_real_dir(&target) && has_subdir(&source)? {
                self.place(&source, &target)?;
                continue;
            }
            if exists {
                let kept = self.old.join(self.steps.len().to_string());
                self.rename(&target, &kept)?;
                self.steps.push(Step::Aside { target: target.clone(), kept });
            }
            self.rename(&source, &target)?;
            self.steps.push(Step::Placed { source, target });
        }
        Ok(())
    }

    /// Undoes every move, the last first (renames back; one that fails is skipped, and
    /// what it would have restored stays in the staging directory).
    fn undo(&mut self) {
        while let Some(step) = self.steps.pop() {
            let _ = match step {
                Step::Placed { source, target } => fs::rename(target, source),
                Step::Aside { target, kept } => fs::rename(kept, target),
            };
        }
    }
}

/// Installs the handler of SIGINT, SIGTERM and SIGHUP for this process (the command line
/// calls it once): it waits for the files being staged and for a commit in progress (which
/// rolls back), removes every staging directory of the process and exits with 128 + the
/// signal's number. Without it a signal kills the run at once, and the next run into the
/// same directory removes what it left.
#[cfg(unix)]
pub fn remove_staging_on_signals() -> Result<(), Error> {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP])
        .map_err(|source| Error::Io { path: "(signal handler)".into(), source })?;
    std::thread::Builder::new()
        .name("mechdraw-signals".into())
        .spawn(move || {
            if let Some(signal) = signals.forever().next() {
                INTERRUPTED.store(true, Ordering::SeqCst);
                // Held until the process exits: nothing is staged or moved after this.
                let _gate = GATE.write().unwrap_or_else(std::sync::PoisonError::into_inner);
                for staging in live().iter() {
                    let _ = fs::remove_dir_all(staging);
                }
                std::process::exit(128 + signal);
            }
        })
        .map_err(|source| Error::Io { path: "(signal handler)".into(), source })?;
    Ok(())
}

/// Elsewhere than on Unix the system's default handling stays (the next run removes what an
/// interrupted one left).
#[cfg(not(unix))]
pub fn remove_staging_on_signals() -> Result<(), Error> {
    Ok(())
}

/// Creates (or truncates) the file `path` and writes `pieces` into it one after the other,
/// as few system calls as the kernel takes them in (one for a frame's two pieces).
fn write_pieces(path: &Path, pieces: &[&[u8]]) -> std::io::Result<()> {
    use std::io::{IoSlice, Write};
    let mut file = File::create(path)?;
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

impl super::bytes::Sink for Output {
    fn put(&self, files: &[super::bytes::File<'_>]) -> Result<(), Error> {
        // Listed by the caller, in the canonical order (see `record_paths`).
        self.stage(files)
    }
}

impl Drop for Output {
    fn drop(&mut self) {
        if !self.committed {
            let _ = fs::remove_dir_all(&self.staging);
        }
        live().retain(|p| p != &self.staging);
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
        let views: Vec<super::super::bytes::File<'_>> = files
            .iter()
            .map(|(n, b)| {
                (super::super::paths::RelPath::join(&n.split('/').collect::<Vec<_>>()).unwrap(), vec![&b[..1], &b[1..]])
            })
            .collect();
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

    /// A tree of files and their contents under `dir` (the lock-free picture of a directory).
    fn snapshot(dir: &Path) -> Vec<(String, String)> {
        fn walk(base: &Path, dir: &Path, out: &mut Vec<(String, String)>) {
            for e in fs::read_dir(dir).unwrap() {
                let p = e.unwrap().path();
                let rel = p.strip_prefix(base).unwrap().display().to_string();
                if p.is_dir() {
                    out.push((rel + "/", String::new()));
                    walk(base, &p, out);
                } else {
                    out.push((rel, fs::read_to_string(&p).unwrap_or_default()));
                }
            }
        }
        let mut out = Vec::new();
        walk(dir, dir, &mut out);
        out.sort();
        out
    }

    /// An earlier run's outputs: a picture, a table, two scenes' frames.
    fn earlier(dir: &Path) -> Vec<(String, String)> {
        let mut out = Output::new(dir).unwrap();
        out.write("a.svg", "a").unwrap();
        out.write("a.csv", "1").unwrap();
        out.write("frames/a/pos_000.svg", "a0").unwrap();
        out.write("frames/a/pos_001.svg", "a1").unwrap();
        out.write("frames/b/pos_000.svg", "b0").unwrap();
        out.commit().unwrap();
        snapshot(dir)
    }

    #[test]
    fn a_commit_that_fails_at_any_move_leaves_the_directory_as_it_was() {
        // Moves: a.svg aside + in, a.csv aside + in, frames/a aside + in, new.txt in = 7.
        for fail_at in 0..7 {
            let tmp = tempfile::tempdir().unwrap();
            let before = earlier(tmp.path());
            let mut out = Output::new(tmp.path()).unwrap();
            out.write("a.svg", "a'").unwrap();
            out.write("a.csv", "2").unwrap();
            out.write("frames/a/pos_000.svg", "a0'").unwrap();
            out.write("new.txt", "n").unwrap();
            let mut k = 0;
            let e = out
                .commit_with(&mut |_| {
                    k += 1;
                    if k > fail_at { Err(std::io::Error::other("injected")) } else { Ok(()) }
                })
                .unwrap_err();
            assert!(e.to_string().contains("injected"), "{e}");
            assert_eq!(snapshot(tmp.path()), before, "failing at move {fail_at}");
        }
    }

    #[test]
    fn something_of_another_type_in_the_way_is_refused_before_any_move() {
        let tmp = tempfile::tempdir().unwrap();
        let _ = earlier(tmp.path());
        fs::create_dir_all(tmp.path().join("z.svg/x")).unwrap();
        let before = snapshot(tmp.path());
        let mut out = Output::new(tmp.path()).unwrap();
        out.write("a.svg", "a'").unwrap();
        out.write("z.svg", "z").unwrap();
        let e = out.commit().unwrap_err().to_string();
        assert!(e.contains("z.svg") && e.contains("a directory is in the way"), "{e}");
        assert_eq!(snapshot(tmp.path()), before);
    }

    #[test]
    fn only_plain_relative_paths_are_staged() {
        let tmp = tempfile::tempdir().unwrap();
        let mut out = Output::new(tmp.path().join("out").as_path()).unwrap();
        for bad in ["../x", "/tmp/x", "a/../../x", "", "a//b", "a/", ".", "a/./b"] {
            let e = out.write(bad, "x").unwrap_err();
            assert!(matches!(e, Error::OutputPath { .. }), "{bad}: {e}");
        }
        drop(out);
        assert_eq!(snapshot(tmp.path()), vec![("out/".to_string(), String::new())]);
    }

    #[test]
    fn a_later_run_removes_the_staging_of_a_dead_run_and_keeps_a_live_ones() {
        let tmp = tempfile::tempdir().unwrap();
        // A dead run's: its lock file is there, and nobody holds it.
        let dead = tmp.path().join(format!("{STAGING_PREFIX}999999-0"));
        fs::create_dir_all(dead.join("new/frames")).unwrap();
        fs::write(dead.join("lock"), "").unwrap();
        fs::write(dead.join("new/frames/pos_000.svg"), "x").unwrap();
        // A live one's (this process's own output, not yet committed).
        let mut live = Output::new(tmp.path()).unwrap();
        live.write("a.txt", "x").unwrap();
        assert!(!dead.exists(), "the dead run's staging is removed");
        let out = Output::new(tmp.path()).unwrap();
        assert!(live.staging.exists(), "a live run's staging is kept");
        drop(out);
        live.commit().unwrap();
        assert_eq!(snapshot(tmp.path()), vec![("a.txt".to_string(), "x".to_string())]);
    }
}
