//! PDF files compared by page count and each page's text. The pages' drawings are not
//! compared here: every PDF mechdraw writes (`<name>-sheets.pdf`) has its pages as SVG twins
//! (`sheets/<name>/<position>.svg`), which are compared pixel by pixel.
//!
//! A small reader for the PDFs mechdraw writes (krilla's: plain objects, FlateDecode
//! streams, fonts with a ToUnicode CMap) and others of that shape: the page tree from the
//! root `/Pages`, each page's content streams, the strings of its text operators decoded
//! through its fonts' CMaps. A PDF it cannot read is reported as such, with its page count
//! when it finds one.

use std::collections::HashMap;
use std::io::Read;

use super::{DiffError, FileDiff, Pair, Verdict};

/// An object: its dictionary's text and its stream's raw bytes.
struct Object<'a> {
    dict: &'a [u8],
    stream: Option<&'a [u8]>,
}

/// The objects of a PDF by number.
struct Doc<'a> {
    objects: HashMap<u32, Object<'a>>,
}

fn find(hay: &[u8], needle: &[u8], from: usize) -> Option<usize> {
    hay.get(from..)?.windows(needle.len()).position(|w| w == needle).map(|i| i + from)
}

impl<'a> Doc<'a> {
    fn parse(bytes: &'a [u8]) -> Doc<'a> {
        let mut objects = HashMap::new();
        let mut at = 0;
        while let Some(i) = find(bytes, b" 0 obj", at) {
            let start = bytes[..i].iter().rposition(|b| !b.is_ascii_digit()).map_or(0, |p| p + 1);
            let number = std::str::from_utf8(&bytes[start..i]).ok().and_then(|s| s.parse().ok());
            let body = i + b" 0 obj".len();
            let end = find(bytes, b"endobj", body).unwrap_or(bytes.len());
            let text = &bytes[body..end];
            let (dict, stream) = match find(text, b"stream", 0) {
                Some(s) => {
                    let mut data = s + b"stream".len();
                    if text.get(data) == Some(&b'\r') {
                        data += 1;
                    }
                    if text.get(data) == Some(&b'\n') {
                        data += 1;
                    }
                    let stop = find(text, b"endstream", data).unwrap_or(text.len());
                    (&text[..s], Some(&text[data.min(stop)..stop]))
                }
                None => (text, None),
            };
            if let Some(n) = number {
                objects.insert(n, Object { dict, stream });
            }
            at = end;
        }
        Doc { objects }
    }

    /// The object a `/Key N 0 R` in `dict` refers to.
    fn reference(&self, dict: &[u8], key: &[u8]) -> Option<&Object<'a>> {
        self.objects.get(&reference_number(dict, key)?)
    }

    /// A stream's bytes, inflated when it says FlateDecode.
    fn stream(&self, o: &Object<'a>) -> Option<Vec<u8>> {
        let raw = o.stream?;
        if find(o.dict, b"FlateDecode", 0).is_none() {
            return Some(raw.to_vec());
        }
        let mut out = Vec::new();
        flate2::read::ZlibDecoder::new(raw).read_to_end(&mut out).ok()?;
        Some(out)
    }

    /// The pages in order, from the root of the page tree.
    fn pages(&self) -> Vec<&Object<'a>> {
        let root = self.objects.values().find(|o| is_type(o.dict, b"Pages") && find(o.dict, b"/Parent", 0).is_none());
        let mut out = Vec::new();
        if let Some(r) = root {
            self.kids(r, &mut out, 0);
        }
        out
    }

    fn kids<'s>(&'s self, node: &Object<'a>, out: &mut Vec<&'s Object<'a>>, depth: usize) {
        let Some(list) = array_after(node.dict, b"/Kids") else { return };
        for n in reference_list(list) {
            let Some(kid) = self.objects.get(&n) else { continue };
            if is_type(kid.dict, b"Pages") && depth < 32 {
                self.kids(kid, out, depth + 1);
            } else {
                out.push(kid);
            }
        }
    }
}

fn is_type(dict: &[u8], t: &[u8]) -> bool {
    let mut pat = b"/Type/".to_vec();
    pat.extend_from_slice(t);
    let mut spaced = b"/Type /".to_vec();
    spaced.extend_from_slice(t);
    [pat, spaced]
        .iter()
        .any(|p| find(dict, p, 0).is_some_and(|i| !dict.get(i + p.len()).is_some_and(|c| c.is_ascii_alphanumeric())))
}

/// `N` of `/Key N 0 R` in `dict`.
fn reference_number(dict: &[u8], key: &[u8]) -> Option<u32> {
    let i = find(dict, key, 0)? + key.len();
    let rest = std::str::from_utf8(&dict[i..]).ok()?;
    let mut words = rest.split_whitespace();
    let n = words.next()?.parse().ok()?;
    (words.next()? == "0" && words.next()?.starts_with('R')).then_some(n)
}

/// The text of the array `[...]` after `key`.
fn array_after<'b>(dict: &'b [u8], key: &[u8]) -> Option<&'b [u8]> {
    let i = find(dict, key, 0)? + key.len();
    let open = i + dict[i..].iter().position(|&b| b == b'[')?;
    let close = open + dict[open..].iter().position(|&b| b == b']')?;
    Some(&dict[open + 1..close])
}

/// `N 0 R` references in a list.
fn reference_list(list: &[u8]) -> Vec<u32> {
    let text = String::from_utf8_lossy(list).replace('R', " R ");
    let words: Vec<&str> = text.split_whitespace().collect();
    words.windows(3).filter(|w| w[2] == "R").filter_map(|w| w[0].parse().ok()).collect()
}

/// A font's map from character codes to text, and the codes' width in bytes.
struct CMap {
    bytes: usize,
    map: HashMap<u32, String>,
}

fn hex_value(h: &[u8]) -> Option<u32> {
    u32::from_str_radix(std::str::from_utf8(h).ok()?, 16).ok()
}

fn hex_text(h: &[u8]) -> String {
    let units: Vec<u16> = h.chunks(4).filter_map(|c| hex_value(c).map(|v| v as u16)).collect();
    String::from_utf16_lossy(&units)
}

/// The `<...>` hex strings of a CMap's text, in order.
fn hex_strings(text: &[u8]) -> Vec<&[u8]> {
    let mut out = Vec::new();
    let mut i = 0;
    while let Some(o) = text[i..].iter().position(|&b| b == b'<') {
        let s = i + o + 1;
        let Some(e) = text[s..].iter().position(|&b| b == b'>') else { break };
        out.push(&text[s..s + e]);
        i = s + e + 1;
    }
    out
}

fn parse_cmap(text: &[u8]) -> CMap {
    let mut map = HashMap::new();
    let mut bytes = 2;
    let section = |begin: &[u8], end: &[u8], from: usize| -> Option<(usize, usize)> {
        let s = find(text, begin, from)? + begin.len();
        Some((s, find(text, end, s)?))
    };
    if let Some((s, e)) = section(b"begincodespacerange", b"endcodespacerange", 0)
        && let Some(h) = hex_strings(&text[s..e]).first()
    {
        bytes = h.len().div_ceil(2).max(1);
    }
    let mut at = 0;
    while let Some((s, e)) = section(b"beginbfchar", b"endbfchar", at) {
        for pair in hex_strings(&text[s..e]).chunks(2) {
            if let [code, dst] = pair {
                map.extend(hex_value(code).map(|c| (c, hex_text(dst))));
            }
        }
        at = e;
    }
    at = 0;
    while let Some((s, e)) = section(b"beginbfrange", b"endbfrange", at) {
        for triple in hex_strings(&text[s..e]).chunks(3) {
            if let [lo, hi, dst] = triple {
                let (Some(lo), Some(hi), Some(first)) = (hex_value(lo), hex_value(hi), hex_value(dst)) else {
                    continue;
                };
                for (k, c) in (lo..=hi.min(lo + 0xffff)).enumerate() {
                    let ch = char::from_u32(first + k as u32).map(String::from).unwrap_or_default();
                    map.insert(c, ch);
                }
            }
        }
        at = e;
    }
    CMap { bytes, map }
}

/// A page's fonts: resource name → CMap.
fn page_fonts(doc: &Doc<'_>, page: &Object<'_>) -> HashMap<String, CMap> {
    let resources: &[u8] = doc.reference(page.dict, b"/Resources").map_or(page.dict, |o| o.dict);
    let fonts_dict: &[u8] = doc.reference(resources, b"/Font").map_or_else(
        || {
            let i = find(resources, b"/Font", 0).map_or(resources.len(), |i| i + 5);
            let end = find(resources, b">>", i).unwrap_or(resources.len());
            &resources[i..end]
        },
        |o| o.dict,
    );
    let text = String::from_utf8_lossy(fonts_dict).replace('/', " /").replace("<<", " ").replace(">>", " ");
    let words: Vec<&str> = text.split_whitespace().collect();
    let mut out = HashMap::new();
    for w in words.windows(4) {
        if let (Some(name), Ok(n), "0", "R") = (w[0].strip_prefix('/'), w[1].parse::<u32>(), w[2], w[3]) {
            let cmap = doc
                .objects
                .get(&n)
                .and_then(|font| doc.reference(font.dict, b"/ToUnicode"))
                .and_then(|o| doc.stream(o));
            out.insert(name.to_string(), cmap.map_or(CMap { bytes: 1, map: HashMap::new() }, |c| parse_cmap(&c)));
        }
    }
    out
}

/// A literal string `(...)` starting at `s[0] == b'('`: its bytes and the index after it.
fn literal(s: &[u8]) -> (Vec<u8>, usize) {
    let (mut out, mut depth, mut i) = (Vec::new(), 0, 1);
    while i < s.len() {
        match s[i] {
            b'\\' if i + 1 < s.len() => {
                i += 1;
                match s[i] {
                    b'n' => out.push(b'\n'),
                    b'r' => out.push(b'\r'),
                    b't' => out.push(b'\t'),
                    b'b' => out.push(8),
                    b'f' => out.push(12),
                    d @ b'0'..=b'7' => {
                        let mut v = u32::from(d - b'0');
                        for _ in 0..2 {
                            match s.get(i + 1) {
                                Some(&c @ b'0'..=b'7') => {
                                    v = v * 8 + u32::from(c - b'0');
                                    i += 1;
                                }
                                _ => break,
                            }
                        }
                        out.push(v as u8);
                    }
                    b'\n' => {}
                    c => out.push(c),
                }
            }
            b'(' => {
                depth += 1;
                out.push(b'(');
            }
            b')' if depth == 0 => return (out, i + 1),
            b')' => {
                depth -= 1;
                out.push(b')');
            }
            c => out.push(c),
        }
        i += 1;
    }
    (out, i)
}

fn decode(bytes: &[u8], cmap: Option<&CMap>) -> String {
    match cmap {
        Some(c) if !c.map.is_empty() => bytes
            .chunks(c.bytes)
            .map(|ch| {
                let code = ch.iter().fold(0u32, |v, &b| v << 8 | u32::from(b));
                c.map.get(&code).cloned().unwrap_or_else(|| "\u{fffd}".into())
            })
            .collect(),
        _ => bytes.iter().map(|&b| b as char).collect(),
    }
}

/// The text a content stream shows: one line per text object (BT … ET).
fn page_text(content: &[u8], fonts: &HashMap<String, CMap>) -> String {
    let (mut out, mut font, mut last_name, mut i) = (String::new(), None::<&CMap>, String::new(), 0);
    while i < content.len() {
        match content[i] {
            b'(' => {
                let (s, next) = literal(&content[i..]);
                out.push_str(&decode(&s, font));
                i += next;
                continue;
            }
            b'<' if content.get(i + 1) != Some(&b'<') => {
                let end = content[i..].iter().position(|&b| b == b'>').map_or(content.len(), |e| i + e);
                let hex: Vec<u8> = content[i + 1..end].iter().copied().filter(u8::is_ascii_hexdigit).collect();
                let bytes: Vec<u8> = hex.chunks(2).filter_map(|c| hex_value(c).map(|v| v as u8)).collect();
                out.push_str(&decode(&bytes, font));
                i = end + 1;
                continue;
            }
            b'/' => {
                let end = content[i + 1..]
                    .iter()
                    .position(|b| b" /[]()<>\n\r\t".contains(b))
                    .map_or(content.len(), |e| i + 1 + e);
                last_name = String::from_utf8_lossy(&content[i + 1..end]).into_owned();
                i = end;
                continue;
            }
            b'T' if content.get(i + 1) == Some(&b'f') => font = fonts.get(&last_name),
            b'E' if content.get(i + 1) == Some(&b'T') && !out.ends_with('\n') && !out.is_empty() => out.push('\n'),
            _ => {}
        }
        i += 1;
    }
    out
}

/// Each page's text, or `None` where the PDF cannot be read that way.
fn texts(bytes: &[u8]) -> Option<Vec<String>> {
    let doc = Doc::parse(bytes);
    let pages = doc.pages();
    if pages.is_empty() {
        return None;
    }
    pages
        .iter()
        .map(|page| {
            let fonts = page_fonts(&doc, page);
            let contents: Vec<u32> = match array_after(page.dict, b"/Contents") {
                Some(list)
                    if find(page.dict, b"/Contents[", 0).is_some() || find(page.dict, b"/Contents [", 0).is_some() =>
                {
                    reference_list(list)
                }
                _ => reference_number(page.dict, b"/Contents").into_iter().collect(),
            };
            let mut text = String::new();
            for n in contents {
                text.push_str(&page_text(&doc.stream(doc.objects.get(&n)?)?, &fonts));
            }
            Some(text)
        })
        .collect()
}

pub(super) fn compare(pair: &Pair<'_>, old: &[u8], new: &[u8]) -> Result<FileDiff, DiffError> {
    let (Some(a), Some(b)) = (texts(old), texts(new)) else {
        let detail =
            "bytes differ, and its pages could not be read (not a PDF of the shape mechdraw writes)".to_string();
        return Ok(FileDiff::new(pair.rel, Verdict::Changed, vec![detail]));
    };
    let mut details = Vec::new();
    if a.len() != b.len() {
        details.push(format!("{} pages → {}", a.len(), b.len()));
    }
    let differing: Vec<usize> = (0..a.len().min(b.len())).filter(|&k| a[k] != b[k]).collect();
    if let Some(&k) = differing.first() {
        let (la, lb) = a[k].lines().zip(b[k].lines()).find(|(x, y)| x != y).unwrap_or(("(end)", "(end)"));
        details.push(format!(
            "text differs on {} of {} pages, first page {}: {:?} → {:?}",
            differing.len(),
            a.len().min(b.len()),
            k + 1,
            la,
            lb
        ));
    }
    if details.is_empty() {
        details.push(format!(
            "{} pages, the same text on each; the drawings differ (their SVG twins, sheets/…/*.svg, are compared as pictures)",
            a.len()
        ));
        return Ok(FileDiff::new(pair.rel, Verdict::Within, details));
    }
    Ok(FileDiff::new(pair.rel, Verdict::Changed, details))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::draw::{DimStyle, Drawing, pdf as writer};
    use crate::geom::Point;

    fn pdf(texts: &[&str]) -> Vec<u8> {
        let drawings: Vec<Drawing> = texts
            .iter()
            .map(|t| {
                let mut d = Drawing::new(DimStyle { text_height: 2.5, arrow_size: 2.5 });
                d.text(0, Point::new(20.0, 100.0), 5.0, *t);
                d.paper_mm_per_unit = Some(1.0);
                d
            })
            .collect();
        let window = crate::draw::Bounds { min: Point::new(0.0, 0.0), max: Point::new(297.0, 210.0) };
        let pages: Vec<writer::Page<'_>> =
            drawings.iter().map(|d| writer::Page { drawing: d, window, hairline_mm: 0.25 }).collect();
        writer::to_bytes(&pages).unwrap()
    }

    #[test]
    fn our_pdfs_read_back_as_their_pages_text() {
        let t = texts(&pdf(&["φ1 = 90°", "vB = 1.25 m/s"])).unwrap();
        assert_eq!(t, vec!["φ1 = 90°\n".to_string(), "vB = 1.25 m/s\n".to_string()]);
    }

    #[test]
    fn pages_and_texts_are_compared() {
        let p = std::path::Path::new("x.pdf");
        let pair = Pair { rel: "x.pdf", old: p, new: p, tol_rel: 1e-9 };
        let d = compare(&pair, &pdf(&["a", "k_l = 2 mm/mm"]), &pdf(&["a", "k_l = 5 mm/mm"])).unwrap();
        assert_eq!(d.verdict, Verdict::Changed);
        assert!(d.details[0].contains("first page 2: \"k_l = 2 mm/mm\" → \"k_l = 5 mm/mm\""), "{:?}", d.details);
        let d = compare(&pair, &pdf(&["a"]), &pdf(&["a", "b"])).unwrap();
        assert_eq!(d.details[0], "1 pages → 2");
        assert_eq!(compare(&pair, b"%PDF-1.7 broken", b"%PDF-1.7 other").unwrap().verdict, Verdict::Changed);
    }
}
