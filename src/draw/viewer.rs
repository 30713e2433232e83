//! The self-contained HTML viewer: SVG frames with a slider, play/pause and speed, that
//! works from `file://` (everything inline, no network, no external script or font).
//!
//! The frames are embedded as a JSON array of SVG strings; the page shows one at a time
//! in `<div id="stage">`. Its state is readable from the DOM (for people and for the
//! browser test): `#stage[data-frame]` holds the index of the frame shown, and
//! `#frame-label` its label. The URL hash chooses the frame and the mode:
//! `#frame=90` shows frame 90 (through the slider, as a user would), `#play` starts
//! playing, `#frame=10&play` both. Keys: ← → step, space plays/pauses, Home/End.

/// One frame of the viewer.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// Label shown with the slider (e.g. `φ1 = 90°` or `t = 0.250 s`).
    pub label: String,
    /// The frame as an SVG document.
    pub svg: String,
}

/// Escapes text for HTML element content and attribute values.
fn escape_html(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// `s` as a JavaScript string literal that is safe inside `<script>` (JSON escaping, plus
/// `<` written as `\u003c` so no `</script>` can end the block early).
fn js_string(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 16);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            '<' => out.push_str("\\u003c"),
            '\u{2028}' => out.push_str("\\u2028"),
            '\u{2029}' => out.push_str("\\u2029"),
            c if (c as u32) < 0x20 => out.push_str(&format!("\\u{:04x}", c as u32)),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

const STYLE: &str = r#"
body { font-family: "DejaVu Sans", Arial, sans-serif; margin: 0; background: #f4f4f4; color: #222; }
header { padding: 6px 12px; background: #fff; border-bottom: 1px solid #ccc; }
h1 { font-size: 16px; margin: 0 0 4px 0; }
#controls { display: flex; align-items: center; gap: 10px; flex-wrap: wrap; }
#slider { flex: 1; min-width: 200px; }
#frame-label { min-width: 9em; font-variant-numeric: tabular-nums; }
#stage { margin: 8px; background: #fff; border: 1px solid #ccc; }
#stage svg { width: 100%; height: auto; max-height: calc(100vh - 90px); display: block; }
button { min-width: 4.5em; }
"#;

const SCRIPT: &str = r#"
(function () {
  "use strict";
  var stage = document.getElementById("stage");
  var slider = document.getElementById("slider");
  var label = document.getElementById("frame-label");
  var play = document.getElementById("play");
  var speed = document.getElementById("speed");
  var timer = null;
  function show(i) {
    if (FRAMES.length === 0) { return; }
    i = Math.max(0, Math.min(FRAMES.length - 1, i | 0));
    stage.innerHTML = FRAMES[i];
    stage.setAttribute("data-frame", String(i));
    label.textContent = LABELS[i] + "  (" + (i + 1) + "/" + FRAMES.length + ")";
    if (String(slider.value) !== String(i)) { slider.value = String(i); }
  }
  function stop() {
    if (timer !== null) { clearInterval(timer); timer = null; }
    play.textContent = "Play";
    document.body.removeAttribute("data-playing");
  }
  function start() {
    stop();
    var fps = parseFloat(speed.value) || 30;
    timer = setInterval(function () {
      show((parseInt(slider.value, 10) + 1) % FRAMES.length);
    }, 1000 / fps);
    play.textContent = "Pause";
    document.body.setAttribute("data-playing", "1");
  }
  slider.addEventListener("input", function () { show(parseInt(slider.value, 10)); });
  play.addEventListener("click", function () { if (timer === null) { start(); } else { stop(); } });
  speed.addEventListener("change", function () { if (timer !== null) { start(); } });
  document.addEventListener("keydown", function (e) {
    var i = parseInt(slider.value, 10);
    if (e.key === "ArrowRight") { stop(); show((i + 1) % FRAMES.length); }
    else if (e.key === "ArrowLeft") { stop(); show((i - 1 + FRAMES.length) % FRAMES.length); }
    else if (e.key === "Home") { stop(); show(0); }
    else if (e.key === "End") { stop(); show(FRAMES.length - 1); }
    else if (e.key === " ") { e.preventDefault(); play.click(); }
  });
  function fromHash() {
    var h = window.location.hash.replace(/^#/, "");
    var wantPlay = false, frame = null;
    h.split("&").forEach(function (part) {
      var kv = part.split("=");
      if (kv[0] === "frame" && kv.length > 1 && /^[0-9]+$/.test(kv[1])) { frame = parseInt(kv[1], 10); }
      if (kv[0] === "play") { wantPlay = true; }
    });
    if (frame !== null) {
      // Move the slider as a user would, then let its input handler show the frame.
      slider.value = String(Math.min(frame, FRAMES.length - 1));
      slider.dispatchEvent(new Event("input"));
    }
    if (wantPlay) { start(); }
  }
  window.addEventListener("hashchange", fromHash);
  slider.max = String(Math.max(0, FRAMES.length - 1));
  show(0);
  fromHash();
})();
"#;

/// The viewer page for `frames`, titled `title`: one HTML document with the frames,
/// the style and the script inline (opens from `file://` without a network).
pub fn html(title: &str, frames: &[Frame]) -> String {
    let total: usize = frames.iter().map(|f| f.svg.len() + f.label.len() + 8).sum();
    let mut s = String::with_capacity(total + 8192);
    let t = escape_html(title);
    s.push_str("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n");
    s.push_str("<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n");
    s.push_str(&format!("<title>{t}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n"));
    s.push_str(&format!("<header>\n<h1>{t}</h1>\n<div id=\"controls\">\n"));
    s.push_str("<button id=\"play\" type=\"button\">Play</button>\n");
    s.push_str(&format!(
        "<input id=\"slider\" type=\"range\" min=\"0\" max=\"{}\" step=\"1\" value=\"0\" aria-label=\"frame\">\n",
        frames.len().saturating_sub(1)
    ));
    s.push_str("<span id=\"frame-label\"></span>\n<label>speed <select id=\"speed\">");
    for (fps, name) in [(5, "5 frames/s"), (15, "15 frames/s"), (30, "30 frames/s"), (60, "60 frames/s")] {
        let sel = if fps == 30 { " selected" } else { "" };
        s.push_str(&format!("<option value=\"{fps}\"{sel}>{name}</option>"));
    }
    s.push_str("</select></label>\n</div>\n</header>\n");
    s.push_str("<div id=\"stage\" data-frame=\"0\"></div>\n<script>\nvar FRAMES = [\n");
    for (i, f) in frames.iter().enumerate() {
        if i > 0 {
            s.push_str(",\n");
        }
        s.push_str(&js_string(&f.svg));
    }
    s.push_str("\n];\nvar LABELS = [");
    for (i, f) in frames.iter().enumerate() {
        if i > 0 {
            s.push(',');
        }
        s.push_str(&js_string(&f.label));
    }
    s.push_str("];\n");
    s.push_str(SCRIPT);
    s.push_str("</script>\n</body>\n</html>\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_are_embedded_safely_and_nothing_is_loaded_from_outside() {
        let frames = vec![
            Frame { label: "φ1 = 0°".into(), svg: "<svg><text>a</script>\"b\\</text></svg>".into() },
            Frame { label: "φ1 = 1°".into(), svg: "<svg/>".into() },
        ];
        let page = html("four <bar>", &frames);
        // The only </script> is the one that closes the block.
        assert_eq!(page.matches("</script>").count(), 1);
        assert!(page.contains("<title>four &lt;bar&gt;</title>"));
        assert!(page.contains(r#"max="1""#));
        assert!(page.contains(r#"id="frame-label""#) && page.contains(r#"data-frame="0""#));
        for external in ["src=", "href=", "http://", "https://", "@import"] {
            assert!(!page.contains(external), "page refers to something outside: {external}");
        }
    }

    #[test]
    fn js_strings_escape_quotes_backslashes_and_controls() {
        assert_eq!(js_string("a\"b\\c\n\u{1}<"), "\"a\\\"b\\\\c\\n\\u0001\\u003c\"");
    }
}
