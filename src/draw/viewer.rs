//! The self-contained HTML viewer: SVG frames with a slider, play/pause and speed, that
//! works from `file://` (everything inline, no network, no external script or font).
//!
//! The frames are embedded as JavaScript data (each distinct SVG line once, each frame as
//! the list of its lines, since consecutive frames share most of their lines); the page
//! shows one at a time in `<div id="stage">`. Its state is readable from the DOM (for people and for the
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
#[cfg(test)]
fn js_string(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 16);
    push_js_string(&mut out, s);
    out
}

/// Appends `s` as a JavaScript string literal (see [`js_string`]), copying runs of plain
/// characters at once.
fn push_js_string(out: &mut String, s: &str) {
    // The bytes that start an escape: controls, `"`, `\\`, `<`, and 0xE2, the first byte of
    // U+2028 and U+2029 (and of other characters, which pass as they are).
    const SPECIAL: [bool; 256] = {
        let mut t = [false; 256];
        let mut b = 0;
        while b < 0x20 {
            t[b] = true;
            b += 1;
        }
        t[b'"' as usize] = true;
        t[b'\\' as usize] = true;
        t[b'<' as usize] = true;
        t[0xE2] = true;
        t
    };
    const HEX: &[u8; 16] = b"0123456789abcdef";
    out.reserve(s.len() + 2);
    out.push('"');
    let mut plain = 0;
    // Byte by byte: every character escaped is ASCII except U+2028 and U+2029, whose UTF-8
    // starts with 0xE2 (never a continuation byte, so `i` is always a character boundary).
    for (i, &b) in s.as_bytes().iter().enumerate() {
        if !SPECIAL[usize::from(b)] {
            continue;
        }
        let (esc, len): (&str, usize) = match b {
            b'"' => ("\\\"", 1),
            b'\\' => ("\\\\", 1),
            b'\n' => ("\\n", 1),
            b'\r' => ("\\r", 1),
            b'\t' => ("\\t", 1),
            b'<' => ("\\u003c", 1),
            0xE2 if s[i..].starts_with('\u{2028}') => ("\\u2028", 3),
            0xE2 if s[i..].starts_with('\u{2029}') => ("\\u2029", 3),
            0xE2 => continue,
            _ => {
                // Another control character: \u00XX.
                out.push_str(&s[plain..i]);
                out.push_str("\\u00");
                out.push(char::from(HEX[usize::from(b >> 4)]));
                out.push(char::from(HEX[usize::from(b & 15)]));
                plain = i + 1;
                continue;
            }
        };
        out.push_str(&s[plain..i]);
        out.push_str(esc);
        plain = i + len;
    }
    out.push_str(&s[plain..]);
    out.push('"');
}

/// Appends the decimal digits of `n`.
fn push_usize(out: &mut String, mut n: usize) {
    let mut buf = [0u8; 20];
    let mut i = buf.len();
    loop {
        i -= 1;
        buf[i] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    // ASCII digits.
    out.push_str(std::str::from_utf8(&buf[i..]).unwrap_or_default());
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
  var N = FRAME_PARTS.length;
  function frameSvg(i) {
    return FRAME_PARTS[i].map(function (k) { return PARTS[k]; }).join("\n");
  }
  function show(i) {
    if (N === 0) { return; }
    i = Math.max(0, Math.min(N - 1, i | 0));
    stage.innerHTML = frameSvg(i);
    stage.setAttribute("data-frame", String(i));
    label.textContent = LABELS[i] + "  (" + (i + 1) + "/" + N + ")";
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
      show((parseInt(slider.value, 10) + 1) % N);
    }, 1000 / fps);
    play.textContent = "Pause";
    document.body.setAttribute("data-playing", "1");
  }
  slider.addEventListener("input", function () { show(parseInt(slider.value, 10)); });
  play.addEventListener("click", function () { if (timer === null) { start(); } else { stop(); } });
  speed.addEventListener("change", function () { if (timer !== null) { start(); } });
  document.addEventListener("keydown", function (e) {
    var i = parseInt(slider.value, 10);
    if (N === 0) { return; }
    if (e.key === "ArrowRight") { stop(); show((i + 1) % N); }
    else if (e.key === "ArrowLeft") { stop(); show((i - 1 + N) % N); }
    else if (e.key === "Home") { stop(); show(0); }
    else if (e.key === "End") { stop(); show(N - 1); }
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
      slider.value = String(Math.min(frame, N - 1));
      slider.dispatchEvent(new Event("input"));
    }
    if (wantPlay && N > 0) { start(); }
  }
  window.addEventListener("hashchange", fromHash);
  slider.max = String(Math.max(0, N - 1));
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
    // The frames share most of their lines (the ground, the coupler curve, titles): each
    // distinct line is stored once in PARTS, each frame as the list of its lines' indices.
    let mut index: rustc_hash::FxHashMap<&str, usize> = rustc_hash::FxHashMap::default();
    let mut parts: Vec<&str> = Vec::new();
    let mut lists: Vec<Vec<usize>> = Vec::with_capacity(frames.len());
    for f in frames {
        let list = f
            .svg
            .split('\n')
            .map(|line| {
                *index.entry(line).or_insert_with(|| {
                    parts.push(line);
                    parts.len() - 1
                })
            })
            .collect();
        lists.push(list);
    }
    s.push_str("<div id=\"stage\" data-frame=\"0\"></div>\n<script>\nvar PARTS = [\n");
    // Escaped in parallel, in chunks written in order.
    use rayon::prelude::*;
    let chunks: Vec<String> = parts
        .par_chunks(64)
        .map(|chunk| {
            let mut c = String::with_capacity(chunk.iter().map(|p| p.len() + 16).sum());
            for (i, p) in chunk.iter().enumerate() {
                if i > 0 {
                    c.push_str(",\n");
                }
                push_js_string(&mut c, p);
            }
            c
        })
        .collect();
    for (i, c) in chunks.iter().enumerate() {
        if i > 0 {
            s.push_str(",\n");
        }
        s.push_str(c);
    }
    s.push_str("\n];\nvar FRAME_PARTS = [\n");
    for (i, list) in lists.iter().enumerate() {
        if i > 0 {
            s.push_str(",\n");
        }
        s.push('[');
        for (j, k) in list.iter().enumerate() {
            if j > 0 {
                s.push(',');
            }
            push_usize(&mut s, *k);
        }
        s.push(']');
    }
    s.push_str("\n];\nvar LABELS = [");
    for (i, f) in frames.iter().enumerate() {
        if i > 0 {
            s.push(',');
        }
        push_js_string(&mut s, &f.label);
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
    fn lines_shared_by_frames_are_stored_once() {
        let shared = "<polyline points=\"0,0 1,1 2,0\"/>";
        let frames: Vec<Frame> = (0..3)
            .map(|i| Frame { label: format!("{i}"), svg: format!("<svg>\n{shared}\n<circle r=\"{i}\"/>\n</svg>") })
            .collect();
        let page = html("t", &frames);
        assert_eq!(page.matches("0,0 1,1 2,0").count(), 1);
        // Frame 2 is lines 0 (<svg>), 1 (shared), its own circle, and the closing tag.
        assert!(page.contains("[0,1,5,3]"), "{page}");
    }

    /// The escaping as first written (a match on every byte): the reference.
    fn js_string_by_match(s: &str) -> String {
        let mut out = String::from("\"");
        for c in s.chars() {
            match c {
                '"' => out.push_str("\\\""),
                '\\' => out.push_str("\\\\"),
                '\n' => out.push_str("\\n"),
                '\r' => out.push_str("\\r"),
                '\t' => out.push_str("\\t"),
                '<' => out.push_str("\\u003c"),
                c if (c as u32) < 0x20 => out.push_str(&format!("\\u{:04x}", c as u32)),
                '\u{2028}' => out.push_str("\\u2028"),
                '\u{2029}' => out.push_str("\\u2029"),
                c => out.push(c),
            }
        }
        out.push('"');
        out
    }

    #[test]
    fn js_strings_escape_every_character_as_a_match_on_each_does() {
        let mut text = String::new();
        for c in (0u32..0x300).chain(0x2000..0x2100).chain([0x1F600, 0x10FFFF]).filter_map(char::from_u32) {
            text.push(c);
            text.push('a');
        }
        assert_eq!(js_string(&text), js_string_by_match(&text));
        for chunk in ["", "\u{2028}", "x\u{2029}", "\u{2027}\u{202a}", "é\u{1f}\u{7f}"] {
            assert_eq!(js_string(chunk), js_string_by_match(chunk), "{chunk:?}");
        }
    }

    #[test]
    fn js_strings_escape_quotes_backslashes_and_controls() {
        assert_eq!(js_string("a\"b\\c\n\u{1}<"), "\"a\\\"b\\\\c\\n\\u0001\\u003c\"");
        // Line and paragraph separators end a JavaScript line; other characters pass as they are.
        assert_eq!(js_string("φ\u{2028}°\u{2029}\u{2027}"), "\"φ\\u2028°\\u2029\u{2027}\"");
    }
}
