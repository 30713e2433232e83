//! The products seam: every kind hands over one `Products` value and one module turns it
//! into files. Checked here for every template, through the library: the files on disk are
//! the in-memory bytes (what a browser download would get), listed in one order; the JSON
//! ends with one newline; `--png` gives a PNG of the picture, of every extra sheet and of
//! every diagram, all one width; each sheet is `<name>-<suffix>.dxf/.svg/.png`, right after
//! the picture; a motion's frames (written as the shared part with each position spliced on) are
//! the SVG writer's output for the whole frame.

mod common;

use std::collections::BTreeSet;
use std::path::Path;

use mechdraw::draw::svg::{self, SvgOptions};
use mechdraw::run::bytes::{self, FRAME_WIDTH_PX, WriteOptions};
use mechdraw::run::products::{Picture, Sheet};
use mechdraw::run::{PNG_WIDTH_PX, RunOptions};
use mechdraw::scene::{self, Override};

/// Every template, with fewer positions and samples so that the whole set runs in seconds.
fn templates() -> Vec<(String, scene::Loaded)> {
    let mut out = Vec::new();
    let paths = common::template_paths();
    for path in paths {
        let text = std::fs::read_to_string(&path).unwrap();
        let kind = text.lines().find_map(|l| l.strip_prefix("kind = ")).unwrap().trim_matches('"').to_string();
        let set: Vec<&str> = match kind.as_str() {
            "fourbar" => vec!["phi1_deg.step=30"],
            "linkage" => vec!["time.steps=12"],
            "chain" => vec!["stackup.samples=20000"],
            _ => vec![],
        };
        let over: Vec<Override> = set.iter().map(|s| s.parse().unwrap()).collect();
        let loaded = scene::load(&path, &over).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        out.push((path.file_stem().unwrap().to_string_lossy().into_owned(), loaded));
    }
    assert!(out.len() >= 7, "templates missing");
    out
}

/// The run's options for a template: a synthesis's design (a motion of its own, 360
/// positions) draws every 30th, as the reduced four-bars do.
fn options(loaded: &scene::Loaded) -> RunOptions {
    let positions = matches!(loaded.scene, scene::Scene::Synthesis(_)).then(|| "every=30".parse().unwrap());
    RunOptions { positions, ..RunOptions::default() }
}

#[test]
fn files_on_disk_are_the_in_memory_bytes_for_every_template() {
    for (stem, loaded) in templates() {
        let tmp = tempfile::tempdir().unwrap();
        let opts = RunOptions { out_dir: Some(tmp.path().to_path_buf()), png: true, ..options(&loaded) };
        let outcome = mechdraw::run::run(&loaded, &opts).unwrap();
        let products = mechdraw::run::products(&loaded, &opts).unwrap();
        let memory = bytes::to_files(&products, &WriteOptions { png: true, ..WriteOptions::default() }).unwrap();

        let mut disk = Vec::new();
        common::read_tree(tmp.path(), Path::new(""), &mut disk);
        let page = common::take_live_page(&mut disk, loaded.scene.name());
        assert!(page.contains(&format!("name = \"{}\"", loaded.scene.name())), "{stem}: the page carries the scene");
        let on_disk: BTreeSet<&str> = disk.iter().map(|(n, _)| n.as_str()).collect();
        let in_memory: BTreeSet<&str> = memory.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(on_disk, in_memory, "{stem}: file sets differ");
        for (name, b) in &disk {
            let m = &memory.iter().find(|(n, _)| n == name).unwrap().1;
            assert!(m == b, "{stem}: {name} differs between disk and memory");
        }
        // `written` lists every file once, in the in-memory order.
        let written: Vec<String> = outcome
            .written
            .iter()
            .map(|p| p.strip_prefix(tmp.path()).unwrap().to_string_lossy().replace('\\', "/"))
            .collect();
        let page = format!("{}.html", loaded.scene.name());
        let order: Vec<&str> = memory.iter().map(|(n, _)| n.as_str()).chain([page.as_str()]).collect();
        assert_eq!(written, order, "{stem}: written order (the live page last)");

        // The JSON: the summary, pretty, one final newline.
        let json = &memory.iter().find(|(n, _)| *n == format!("{}.json", loaded.scene.name())).unwrap().1;
        let text = std::str::from_utf8(json).unwrap();
        assert!(text.ends_with("}\n") && !text.ends_with("\n\n"), "{stem}: JSON must end with one newline");
        let parsed: serde_json::Value = serde_json::from_str(text).unwrap();
        assert_eq!(parsed, outcome.summary, "{stem}: JSON file is the summary");

        // --png: the picture and every diagram, all PNG_WIDTH_PX wide.
        let name = loaded.scene.name();
        assert!(in_memory.contains(format!("{name}.png").as_str()), "{stem}: no picture PNG");
        for (n, b) in memory.iter().filter(|(n, _)| n.ends_with(".png")) {
            assert_eq!(&b[..8], b"\x89PNG\r\n\x1a\n", "{stem}: {n} is not a PNG");
            let width = u32::from_be_bytes([b[16], b[17], b[18], b[19]]);
            assert_eq!(width, PNG_WIDTH_PX, "{stem}: {n} width");
            let svg_name = n.replace(".png", ".svg");
            assert!(in_memory.contains(svg_name.as_str()), "{stem}: {n} has no SVG");
        }
        for sh in &products.sheets {
            for ext in ["dxf", "svg", "png"] {
                let f = format!("{name}-{}.{ext}", sh.suffix);
                assert!(in_memory.contains(f.as_str()), "{stem}: no sheet file {f}");
            }
        }
        for d in &products.diagrams {
            assert!(in_memory.contains(format!("diagrams/{name}/{}.svg", d.stem).as_str()), "{stem}: {}", d.stem);
            assert!(in_memory.contains(format!("diagrams/{name}/{}.png", d.stem).as_str()), "{stem}: {}", d.stem);
        }
        // Nothing but the listed files at the top level besides the scene's own names.
        for n in &on_disk {
            let top = n.split('/').next().unwrap();
            assert!(
                top.starts_with(name) || top == "diagrams" || top == "frames",
                "{stem}: {n} is not under the scene's name, diagrams/ or frames/"
            );
            if let Some(rest) = n.strip_prefix("diagrams/").or_else(|| n.strip_prefix("frames/")) {
                // A synthesis's design is a scene of its own, written under its own name.
                let mut names = vec![name.to_string()];
                names.extend(products.derived.iter().map(|d| d.name.clone()));
                assert!(
                    names.iter().any(|s| rest.starts_with(&format!("{s}/"))),
                    "{stem}: {n} outside its scene's folder"
                );
            }
        }
    }
}

#[test]
fn spliced_frames_are_the_svg_writers_output_for_the_whole_frame() {
    let mut animated = 0;
    for (stem, loaded) in templates() {
        let products = mechdraw::run::products(&loaded, &options(&loaded)).unwrap();
        let Picture::Motion(a) = &products.picture else { continue };
        animated += 1;
        let files = bytes::to_files(&products, &WriteOptions::default()).unwrap();
        let opts = SvgOptions { width_px: FRAME_WIDTH_PX, window: Some(a.window(&a.poses())), ..SvgOptions::default() };
        assert!(!a.is_empty(), "{stem}: no positions");
        for k in 0..a.len() {
            let whole = svg::to_string(&a.frame_of(&a.pose(k)), &opts);
            let name = format!("frames/{}/{}.svg", products.name, a.names[k].to_lowercase());
            let frame = &files.iter().find(|(n, _)| *n == name).unwrap_or_else(|| panic!("{stem}: no {name}")).1;
            assert!(frame == whole.as_bytes(), "{stem}: {name} is not the whole frame");
        }
        // The picture is the first frame.
        let picture = &files.iter().find(|(n, _)| *n == format!("{}.svg", products.name)).unwrap().1;
        assert!(picture == &svg::to_string(&a.frame_of(&a.pose(0)), &opts).into_bytes(), "{stem}: picture");
    }
    assert_eq!(animated, 8, "two four-bar and six linkage templates animate");
}

#[test]
fn without_frames_a_motion_writes_no_frame_and_no_viewer() {
    let (_, loaded) = templates().into_iter().find(|(s, _)| s == "fourbar-chebyshev").unwrap();
    let products = mechdraw::run::products(&loaded, &RunOptions::default()).unwrap();
    let files = bytes::to_files(&products, &WriteOptions { no_frames: true, ..WriteOptions::default() }).unwrap();
    assert!(files.iter().all(|(n, _)| !n.starts_with("frames/") && !n.ends_with(".html")));
    let names: Vec<&str> = files.iter().map(|(n, _)| n.as_str()).collect();
    // The picture, the sheets (the centres and Joukowski's lever), the table, the summary.
    assert_eq!(
        &names[..8],
        [
            "fourbar-chebyshev.dxf",
            "fourbar-chebyshev.svg",
            "fourbar-chebyshev-centres.dxf",
            "fourbar-chebyshev-centres.svg",
            "fourbar-chebyshev-joukowski.dxf",
            "fourbar-chebyshev-joukowski.svg",
            "fourbar-chebyshev.csv",
            "fourbar-chebyshev.json"
        ]
    );
}

#[test]
fn sheets_are_written_like_the_picture_right_after_it() {
    let (_, loaded) = templates().into_iter().find(|(s, _)| s.starts_with("chain")).unwrap();
    let mut products = mechdraw::run::products(&loaded, &RunOptions::default()).unwrap();
    let Picture::Still(d) = &products.picture else { panic!("a chain draws a still picture") };
    let d = d.clone();
    products.sheets = vec![
        Sheet { suffix: "first".into(), drawing: d.clone() },
        Sheet { suffix: "second".into(), drawing: d.clone() },
    ];
    let name = products.name.clone();
    let files = bytes::to_files(&products, &WriteOptions { png: true, ..WriteOptions::default() }).unwrap();
    let names: Vec<&str> = files.iter().map(|(n, _)| n.as_str()).collect();
    let expected: Vec<String> = ["", "-first", "-second"]
        .iter()
        .flat_map(|s| ["dxf", "svg", "png"].map(|e| format!("{name}{s}.{e}")))
        .collect();
    assert_eq!(&names[..9], expected.iter().map(String::as_str).collect::<Vec<_>>().as_slice());
    // A sheet's bytes are the picture's bytes for the same drawing.
    for ext in ["dxf", "svg", "png"] {
        let of = |n: String| &files.iter().find(|(f, _)| *f == n).unwrap().1;
        assert!(of(format!("{name}.{ext}")) == of(format!("{name}-first.{ext}")), "{ext}");
    }
}

#[test]
fn with_png_every_svg_has_its_png_next_to_it_frames_and_printed_pages_too() {
    let (_, loaded) = templates().into_iter().find(|(s, _)| s == "fourbar-chebyshev").unwrap();
    let opts = RunOptions { sheets: Some(mechdraw::figure::shared::sheet::Paper::A4), ..RunOptions::default() };
    let products = mechdraw::run::products(&loaded, &opts).unwrap();
    let files = bytes::to_files(&products, &WriteOptions { png: true, ..WriteOptions::default() }).unwrap();
    let names: Vec<&str> = files.iter().map(|(n, _)| n.as_str()).collect();
    let of = |n: &str| &files.iter().find(|(f, _)| f == n).unwrap_or_else(|| panic!("no {n}")).1;
    let (mut frames, mut pages) = (0, 0);
    for (i, n) in names.iter().enumerate() {
        let Some(stem) = n.strip_suffix(".svg") else { continue };
        frames += usize::from(stem.starts_with("frames/"));
        pages += usize::from(stem.starts_with("sheets/"));
        // The PNG comes right after its SVG and is that SVG rasterised at PNG_WIDTH_PX.
        let png = format!("{stem}.png");
        assert_eq!(names.get(i + 1), Some(&png.as_str()), "{n} is not followed by its PNG");
        let svg = std::str::from_utf8(of(n)).unwrap();
        assert!(of(&png) == &mechdraw::draw::raster::to_png(svg, PNG_WIDTH_PX).unwrap(), "{png}");
    }
    // 12 positions at a 30° step: a frame and three printed pages (mechanism, polygons,
    // forces) for each.
    assert_eq!((frames, pages), (12, 36));
}
