//! DXF files compared entity by entity, read as group-code pairs (any version: R12's
//! POLYLINE/VERTEX as much as R2000's LWPOLYLINE): the entities of the ENTITIES and BLOCKS
//! sections are counted per type and layer; when the counts agree, the entities are paired
//! in order and their coordinates (group codes 10–38, in the drawing's millimetres), other
//! numbers (40–59: radii, heights, widths, angles) and texts (1) compared. Coordinates move
//! within the tolerance when `|Δ| ≤ tol_rel ·` the drawing's extent (its largest coordinate).

use std::collections::BTreeMap;

use super::{DiffError, FileDiff, Pair, Spread, Verdict};

/// One entity: its type, layer, numbers by group code (in order) and texts.
#[derive(Debug, Default, Clone, PartialEq)]
struct Entity {
    kind: String,
    layer: String,
    coords: Vec<(u16, f64)>,
    numbers: Vec<(u16, f64)>,
    texts: Vec<String>,
}

/// The entities of a DXF's ENTITIES and BLOCKS sections, in file order.
fn entities(text: &str) -> Result<Vec<Entity>, String> {
    let mut lines = text.lines();
    let mut out = Vec::new();
    let mut section = String::new();
    let mut current: Option<Entity> = None;
    let mut expect_section_name = false;
    while let Some(code) = lines.next() {
        let value = lines.next().ok_or("a group code without its value at the end of the file")?.trim();
        let code: u16 = code.trim().parse().map_err(|_| format!("{:?} is not a group code", code.trim()))?;
        if expect_section_name && code == 2 {
            section = value.to_string();
            expect_section_name = false;
            continue;
        }
        if code == 0 {
            out.extend(current.take());
            match value {
                "SECTION" => expect_section_name = true,
                "ENDSEC" => section.clear(),
                _ if section == "ENTITIES" || section == "BLOCKS" => {
                    current = Some(Entity { kind: value.to_string(), ..Entity::default() });
                }
                _ => {}
            }
            continue;
        }
        let Some(e) = current.as_mut() else { continue };
        match code {
            8 => e.layer = value.to_string(),
            1 => e.texts.push(value.to_string()),
            10..=38 => e.coords.push((code, parse_number(value)?)),
            40..=59 => e.numbers.push((code, parse_number(value)?)),
            _ => {}
        }
    }
    out.extend(current);
    Ok(out)
}

fn parse_number(value: &str) -> Result<f64, String> {
    value.parse().map_err(|_| format!("{value:?} is not a number"))
}

/// Entities per `(type, layer)`.
fn counts(es: &[Entity]) -> BTreeMap<(&str, &str), usize> {
    let mut m = BTreeMap::new();
    for e in es {
        *m.entry((e.kind.as_str(), e.layer.as_str())).or_insert(0) += 1;
    }
    m
}

pub(super) fn compare(pair: &Pair<'_>, old: &[u8], new: &[u8]) -> Result<FileDiff, DiffError> {
    let read = |which: &std::path::Path, bytes: &[u8]| {
        // R12 text is not always UTF-8 (code pages): read it as Latin-1 where it is not.
        let text = String::from_utf8(bytes.to_vec()).unwrap_or_else(|_| bytes.iter().map(|&b| b as char).collect());
        entities(&text).map_err(|e| pair.format_error(which, "DXF", e))
    };
    let (a, b) = (read(pair.old, old)?, read(pair.new, new)?);
    let mut details = Vec::new();
    let (ca, cb) = (counts(&a), counts(&b));
    if ca != cb {
        details.push(format!("{} entities → {}; counts per type and layer differ:", a.len(), b.len()));
        let keys: std::collections::BTreeSet<_> = ca.keys().chain(cb.keys()).collect();
        let changed: Vec<String> = keys
            .into_iter()
            .filter(|k| ca.get(*k) != cb.get(*k))
            .map(|k| format!("  {} on {}: {} → {}", k.0, k.1, ca.get(k).unwrap_or(&0), cb.get(k).unwrap_or(&0)))
            .collect();
        let n = changed.len();
        details.extend(changed.into_iter().take(10));
        if n > 10 {
            details.push(format!("  … and {} more", n - 10));
        }
        return Ok(FileDiff::new(pair.rel, Verdict::Changed, details));
    }
    let (coords, numbers, texts) = pairwise(&a, &b);
    let mut changed = false;
    for (what, spread) in [("coordinates", &coords), ("other numbers (radii, heights, angles)", &numbers)] {
        let (n, _) = spread.beyond(pair.tol_rel);
        if n > 0 {
            changed = true;
            details.push(format!("{what}: {n} moved beyond {:e}; {}", pair.tol_rel, spread.describe()));
        }
    }
    if let Some((n, first)) = texts {
        changed = true;
        details.push(format!("{n} texts differ, first {first}"));
    }
    if !changed {
        details.push(format!("{} entities, each within {:e} (bytes differ)", a.len(), pair.tol_rel));
    }
    Ok(FileDiff::new(pair.rel, if changed { Verdict::Changed } else { Verdict::Within }, details))
}

/// Entities paired in order (same counts per type and layer): spreads of coordinates and of
/// other numbers, and the texts that differ (count, first).
fn pairwise(a: &[Entity], b: &[Entity]) -> (Spread, Spread, Option<(usize, String)>) {
    let (mut coords, mut numbers) = (Spread::default(), Spread::default());
    let (mut texts, mut first_text) = (0, None);
    for (i, (ea, eb)) in a.iter().zip(b).enumerate() {
        let at = |code: u16| format!("entity {} ({} on {}, group {code})", i + 1, eb.kind, eb.layer);
        for (spread, xs, ys) in [(&mut coords, &ea.coords, &eb.coords), (&mut numbers, &ea.numbers, &eb.numbers)] {
            for (&(code, x), &(_, y)) in xs.iter().zip(ys) {
                spread.add(x, y, || at(code));
            }
            if xs.len() != ys.len() {
                spread.add(0.0, f64::INFINITY, || {
                    format!("entity {} ({}): {} → {} values", i + 1, eb.kind, xs.len(), ys.len())
                });
            }
        }
        if ea.texts != eb.texts {
            texts += 1;
            first_text.get_or_insert_with(|| {
                format!("{:?} → {:?} at entity {} ({} on {})", ea.texts, eb.texts, i + 1, eb.kind, eb.layer)
            });
        }
    }
    (coords, numbers, first_text.map(|f| (texts, f)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dxf(x: f64, layer: &str, text: &str) -> String {
        format!(
            "0\nSECTION\n2\nHEADER\n9\n$ACADVER\n1\nAC1009\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n\
             0\nLINE\n8\nMECHANISM\n10\n0.0\n20\n0.0\n11\n{x}\n21\n100.0\n\
             0\nTEXT\n8\n{layer}\n10\n5.0\n20\n5.0\n40\n3.5\n1\n{text}\n0\nENDSEC\n0\nEOF\n"
        )
    }

    fn diff(old: &str, new: &str, tol: f64) -> FileDiff {
        let p = std::path::Path::new("x.dxf");
        compare(&Pair { rel: "x.dxf", old: p, new: p, tol_rel: tol }, old.as_bytes(), new.as_bytes()).unwrap()
    }

    #[test]
    fn entities_are_read_by_type_and_layer_outside_the_header() {
        let es = entities(&dxf(50.0, "POS_000", "B")).unwrap();
        assert_eq!(es.len(), 2);
        assert_eq!((es[0].kind.as_str(), es[0].layer.as_str()), ("LINE", "MECHANISM"));
        assert_eq!(es[0].coords, vec![(10, 0.0), (20, 0.0), (11, 50.0), (21, 100.0)]);
        assert_eq!((es[1].numbers.clone(), es[1].texts.clone()), (vec![(40, 3.5)], vec!["B".to_string()]));
        assert!(entities("0\nSECTION\n2\nENTITIES\n0\nLINE\n10\nx\n").is_err());
    }

    #[test]
    fn a_moved_point_a_new_layer_and_a_new_text_are_named() {
        let d = diff(&dxf(50.0, "POS_000", "B"), &dxf(50.5, "POS_000", "B"), 1e-9);
        assert_eq!(d.verdict, Verdict::Changed);
        assert!(d.details[0].starts_with("coordinates: 1 moved beyond 1e-9; largest |Δ| 0.5"), "{:?}", d.details);
        assert!(d.details[0].contains("entity 1 (LINE on MECHANISM, group 11)"), "{:?}", d.details);
        // 0.5 of a 100 mm drawing: within 1 %.
        assert_eq!(diff(&dxf(50.0, "POS_000", "B"), &dxf(50.5, "POS_000", "B"), 1e-2).verdict, Verdict::Within);
        let d = diff(&dxf(50.0, "POS_000", "B"), &dxf(50.0, "POS_001", "B"), 1.0);
        assert!(d.details.iter().any(|l| l.contains("TEXT on POS_000: 1 → 0")), "{:?}", d.details);
        let d = diff(&dxf(50.0, "POS_000", "B"), &dxf(50.0, "POS_000", "C"), 1.0);
        assert!(d.details[0].starts_with("1 texts differ"), "{:?}", d.details);
    }
}
