//! The page `mechdraw run` writes (the live page, docs/web.md) in a real browser: headless
//! Chromium opens DIR/<name>.html from `file://`, the URL hash moves the slider (`#frame=18`, the page dispatches the slider's
//! `input` event as a user's drag would), and the DOM after the scripts ran shows the
//! frame that was asked for; `#play` advances the frames on its own. A screenshot is kept
//! at target/viewer-screenshot.png for people to look at.
//!
//! Needs Debian's `chromium` (`.ci/test` installs it); the test fails, with the command to
//! install it, when it is missing.

mod common;

use std::path::Path;
use std::process::Command;

use common::{mechdraw, root};

const NAME: &str = "fourbar-chebyshev";

fn chromium() -> String {
    for c in ["chromium", "chromium-browser"] {
        if Command::new(c).arg("--version").output().is_ok_and(|o| o.status.success()) {
            return c.to_string();
        }
    }
    panic!(
        "chromium not found: the viewer test needs a real browser. Install Debian's chromium with \
         `sudo apt-get install -y chromium` (or run `bash .ci/test`, which installs it)"
    );
}

/// Runs headless Chromium on `url` with `extra` arguments; returns stdout.
fn browse(url: &str, extra: &[&str]) -> String {
    let profile = tempfile::tempdir().unwrap();
    let out = Command::new(chromium())
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--disable-dev-shm-usage",
            "--run-all-compositor-stages-before-draw",
            // The page opens its module asynchronously (it inflates it first): the DOM is
            // dumped once the page's tasks have run.
            "--virtual-time-budget=10000",
        ])
        .arg(format!("--user-data-dir={}", profile.path().display()))
        .args(extra)
        .arg(url)
        .output()
        .expect("run chromium");
    assert!(out.status.success(), "chromium failed on {url}:\n{}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// The value of `attr` in the opening tag of the element with `id`, in a dumped DOM.
fn attr_of(dom: &str, id: &str, attr: &str) -> Option<String> {
    let i = dom.find(&format!("id=\"{id}\""))?;
    let start = dom[..i].rfind('<')?;
    let end = i + dom[i..].find('>')?;
    let tag = &dom[start..end];
    let k = tag.find(&format!("{attr}=\""))? + attr.len() + 2;
    Some(tag[k..k + tag[k..].find('"')?].to_string())
}

/// Text content of the element with `id` (no nested elements).
fn text_of(dom: &str, id: &str) -> Option<String> {
    let i = dom.find(&format!("id=\"{id}\""))?;
    let open = i + dom[i..].find('>')? + 1;
    let close = open + dom[open..].find('<')?;
    Some(dom[open..close].to_string())
}

/// The SVG inside the stage.
fn stage_svg(dom: &str) -> String {
    let i = dom.find("id=\"stage\"").expect("stage");
    let s = i + dom[i..].find("<svg").expect("an svg in the stage");
    let e = s + dom[s..].find("</svg>").expect("end of svg");
    dom[s..e].to_string()
}

#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and tesseract: bash .ci/test, or cargo test --features system-tools"
)]
fn viewer_moves_to_the_frame_asked_for_and_plays() {
    let dir = tempfile::tempdir().unwrap();
    let out = mechdraw()
        .arg("run")
        .arg(root().join("templates/fourbar-chebyshev.toml"))
        .arg("--out")
        .arg(dir.path())
        .args(["--set", "phi1_deg.step=5", "-q"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let html: &Path = &dir.path().join(format!("{NAME}.html"));
    let url = format!("file://{}", html.display());

    let first = browse(&url, &["--dump-dom"]);
    assert_eq!(attr_of(&first, "stage", "data-frame").as_deref(), Some("0"), "initial frame");
    let label0 = text_of(&first, "frame-label").unwrap();
    assert!(label0.starts_with("φ1 = 0°"), "label {label0}");

    // Frame 18 of 72 is φ1 = 90°.
    let moved = browse(&format!("{url}#frame=18"), &["--dump-dom"]);
    assert_eq!(attr_of(&moved, "stage", "data-frame").as_deref(), Some("18"), "the slider did not move the frame");
    assert_eq!(attr_of(&moved, "slider", "max").as_deref(), Some("71"));
    let label = text_of(&moved, "frame-label").unwrap();
    assert!(label.starts_with("φ1 = 90°"), "label {label}");
    assert_ne!(stage_svg(&first), stage_svg(&moved), "the picture did not change");
    // The frame shown is the frame file for 90°.
    let file = std::fs::read_to_string(dir.path().join(format!("frames/{NAME}/pos_090.svg"))).unwrap();
    // φ_1 drawn with a subscript (`φ<tspan …>1</tspan>`): read through the tspan, as the
    // SVG's textContent reads `φ1`.
    let plain = |svg: &str| common::svg_plain(svg);
    assert!(plain(&stage_svg(&moved)).contains("φ1 = 90°") && plain(&file).contains("φ1 = 90°"));

    // Playing advances the frames with (virtual) time.
    let played = browse(&format!("{url}#play"), &["--dump-dom"]);
    let f: usize = attr_of(&played, "stage", "data-frame").unwrap().parse().unwrap();
    assert!(f > 0, "playing did not advance the frame");

    let shot = root().join("target/viewer-screenshot.png");
    let _ = std::fs::remove_file(&shot);
    browse(&format!("{url}#frame=18"), &[&format!("--screenshot={}", shot.display()), "--window-size=1200,1000"]);
    let png = std::fs::read(&shot).expect("screenshot written");
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
}

/// Chromium draws a paper-sized frame's text (issue 14 item 2: the metre-sized viewBox
/// drew letters as boxes in some renderers): a screenshot of the 90° frame SVG, opened on
/// its own at 2.5 device pixels per CSS pixel (3.5 mm letters about 33 px high), in a window
/// as wide as the frame (316 mm, about 1200 CSS px), read back by tesseract (`.ci/test`
/// installs tesseract-ocr).
#[test]
#[cfg_attr(
    not(feature = "system-tools"),
    ignore = "needs Chromium and tesseract: bash .ci/test, or cargo test --features system-tools"
)]
fn chromium_renders_a_frames_text() {
    let dir = tempfile::tempdir().unwrap();
    let out = mechdraw()
        .arg("run")
        .arg(root().join("templates/fourbar-chebyshev.toml"))
        .arg("--out")
        .arg(dir.path())
        .args(["--set", "phi1_deg.step=45", "-q"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let svg = dir.path().join(format!("frames/{NAME}/pos_090.svg"));
    let shot = dir.path().join("frame.png");
    browse(
        &format!("file://{}", svg.display()),
        &[
            &format!("--screenshot={}", shot.display()),
            "--window-size=1300,1000",
            "--force-device-scale-factor=2.5",
            "--hide-scrollbars",
        ],
    );
    let out = Command::new("tesseract").arg(&shot).arg("stdout").output().expect("run tesseract");
    assert!(out.status.success(), "tesseract: {}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8_lossy(&out.stdout);
    // The scales' k_v is drawn with a subscript, which tesseract reads as "k,": the unit
    // after it is the scale caption's text (as tests/paper.rs reads it).
    for word in ["Mechanism", "Velocity", "(m/s)/mm"] {
        assert!(text.contains(word), "{word} not read from Chromium's render:\n{text}");
    }
}
