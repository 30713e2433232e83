//! Every template's DXF files (the picture and its sheets) in every version (R12, R2000,
//! R2007) with either dimension encoding (entities, exploded) audit clean with ezdxf:
//! recovered and audited with 0 errors and 0 fixes, every DIMENSION with its own block
//! (issue 29). The templates run at fewer positions (`common::reduced_templates`): the same
//! entities, fewer layers. Each template is solved once and its products written in the six
//! encodings (`run::bytes::to_files`, the bytes `mechdraw run` stages: the DXF options reach
//! only the writer). A synthesis template is run without its design's analysis, and its
//! design file (`<name>-design.toml`, a four-bar or linkage scene) is run apart at the
//! reduced positions: the design's DXF at 360 positions is 10–27 MB a file, the same writer.

mod common;

use mechdraw::draw::dxf::{Dimensions, DxfOptions, DxfVersion};
use mechdraw::run::{self, RunOptions, bytes};
use std::path::{Path, PathBuf};

/// Solves `path` with the `--set` changes `set` once and writes its DXF files in every
/// version and encoding under `target/test-out/dxf_templates/<stem>-<version>-<encoding>/`;
/// returns their paths and, for a synthesis, its design file's text.
fn write_every_encoding(path: &Path, set: &[String], no_analysis: bool) -> (Vec<PathBuf>, Option<String>) {
    let stem = path.file_stem().unwrap().to_string_lossy().into_owned();
    let over: Vec<mechdraw::scene::Override> = set.iter().map(|s| s.parse().unwrap()).collect();
    let loaded = mechdraw::scene::load(path, &over).unwrap_or_else(|e| panic!("{stem}: {e}"));
    let opts = RunOptions { no_frames: true, no_analysis, ..Default::default() };
    let products = run::products(&loaded, &opts).unwrap_or_else(|e| panic!("{stem}: {e}"));
    let (mut files, mut design) = (Vec::new(), None);
    for version in DxfVersion::ALL {
        for dimensions in [Dimensions::Entities, Dimensions::Exploded] {
            let dir = common::root().join("target/test-out/dxf_templates").join(format!(
                "{stem}-{}-{}",
                version.name(),
                dimensions.name()
            ));
            let _ = std::fs::remove_dir_all(&dir);
            let dxf = DxfOptions { version, dimensions, ..Default::default() };
            let wopts = bytes::WriteOptions { png: false, no_frames: true, dxf };
            for (name, data) in bytes::to_files(&products, &wopts).unwrap_or_else(|e| panic!("{stem}: {e}")) {
                if name.ends_with("-design.toml") {
                    design = Some(String::from_utf8(data).unwrap());
                } else if name.ends_with(".dxf") {
                    let file = dir.join(&name);
                    std::fs::create_dir_all(file.parent().unwrap()).unwrap();
                    std::fs::write(&file, data).unwrap();
                    files.push(file);
                }
            }
        }
    }
    (files, design)
}

#[test]
fn every_template_in_every_version_and_encoding_audits_clean() {
    let mut files = Vec::new();
    for (path, set) in common::reduced_templates() {
        let text = std::fs::read_to_string(&path).unwrap();
        let synthesis = text.lines().any(|l| l.trim() == "kind = \"synthesis\"");
        let (written, design) = write_every_encoding(&path, &set, synthesis);
        files.extend(written);
        if synthesis {
            let design = design.unwrap_or_else(|| panic!("{}: no design file", path.display()));
            let stem = path.file_stem().unwrap().to_string_lossy().into_owned();
            let file = common::root().join(format!("target/test-out/dxf_templates/{stem}-design.toml"));
            std::fs::write(&file, &design).unwrap();
            let kind = design.lines().find_map(|l| l.strip_prefix("kind = ")).unwrap().trim_matches('"');
            let set = match kind {
                "fourbar" => vec!["phi1_deg.step=30".to_string()],
                _ => vec!["time.steps=12".to_string()],
            };
            files.extend(write_every_encoding(&file, &set, false).0);
        }
    }
    // Every template, its sheets (the triad's modes, the four-bar's centres and lever), and
    // each synthesis's construction and design.
    assert!(files.len() >= 6 * 12, "{} DXF files", files.len());
    common::assert_ezdxf_clean(&files.iter().map(|p| p.as_path()).collect::<Vec<_>>());
}
