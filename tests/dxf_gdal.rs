//! What GDAL/OGR (QGIS's DXF reader) reads of our text (issue 29): an R2007 file's UTF-8
//! text comes out as written, `φ1 = 75.77°`, because its `$DWGCODEPAGE` says UTF-8
//! (`ANSI_65001`); with `ANSI_1252` GDAL recoded the UTF-8 bytes as Windows-1252 and read
//! `Ï†1 = 75.77Â°`. Needs Debian's `gdal-bin` (`ogrinfo`; `.ci/test` installs it).

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

fn out_dir(name: &str) -> PathBuf {
    let d = common::root().join("target/test-out/dxf_gdal").join(name);
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// `ogrinfo`'s listing of every feature of the DXF (its `Text` fields among them).
fn ogrinfo(dxf: &Path) -> String {
    let out = Command::new("ogrinfo")
        .args(["-ro", "-al", "-q"])
        .arg(dxf)
        .output()
        .expect("run ogrinfo (Debian's gdal-bin; bash .ci/test installs it)");
    assert!(out.status.success(), "ogrinfo {}: {}", dxf.display(), String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).expect("ogrinfo writes UTF-8")
}

#[test]
fn gdal_reads_the_letters_of_an_r2007_file() {
    let dir = out_dir("triad-R2007");
    let out = common::mechdraw()
        .arg("run")
        .arg(common::root().join("templates/triad-popa.toml"))
        .args(["--out", dir.to_str().unwrap(), "--no-frames", "-q", "--dxf-version", "R2007"])
        .output()
        .expect("run mechdraw");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let listing = ogrinfo(&dir.join("triad-popa.dxf"));
    // The angle φ1 (its dimension, expanded by OGR into its block's text) and the caption.
    assert!(listing.contains("Text (String) = φ1 = 75.77°"), "no φ1 = 75.77° in ogrinfo's listing:\n{listing}");
    assert!(listing.contains("→ 75.77°"), "the caption's arrow and degree sign");
    assert!(!listing.contains('Ï') && !listing.contains('Â'), "UTF-8 read as Windows-1252");
}
