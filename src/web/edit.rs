//! Changes to the student's TOML that keep it theirs: a field, a drag or a build step
//! changes the values it means to change and nothing else — the comments (units, sources),
//! the order, the inline tables and the spelling of every other number stay as written.
//!
//! The document is edited with `toml_edit` (format-preserving); the scene is then read from
//! the new text exactly as the command line reads a file, so the page and `mechdraw run`
//! cannot disagree about what the text means.

use super::session::table;
use crate::Error;
use crate::scene::Override;

/// `text` with each `(path, value)` of `changes` written in, in order, as `--set path=value`
/// would change the scene (the same paths, values and refusals): one value changes per
/// change, the rest of the text stays byte for byte.
pub fn set(text: &str, file: &str, changes: &[(String, String)]) -> Result<String, Error> {
    let mut doc = document(text, file)?;
    for (path, value) in changes {
        let o: Override = format!("{path}={value}").parse()?;
        o.apply_to_document(&mut doc)?;
    }
    Ok(doc.to_string())
}

/// The text as a document to edit; a text that is not TOML gives the command line's message.
pub(super) fn document(text: &str, file: &str) -> Result<toml_edit::DocumentMut, Error> {
    // The command line's message (toml's parser), and its line numbers, for a bad text.
    table(text, file)?;
    text.parse::<toml_edit::DocumentMut>().map_err(|e| {
        Error::from(crate::scene::SceneError::Syntax {
            file: file.to_string(),
            message: e.to_string().trim_end().to_string(),
        })
    })
}

/// `v` as a TOML float with at most `decimals` decimals, trailing zeros dropped but one kept
/// (`0.09`, `1.0`, `-12.5`; never `-0.0`): what a drag or a click on the grid writes.
pub fn number(v: f64, decimals: usize) -> String {
    let mut s = format!("{v:.decimals$}");
    if s.contains('.') {
        while s.ends_with('0') {
            s.pop();
        }
        if s.ends_with('.') {
            s.push('0');
        }
    } else {
        s.push_str(".0");
    }
    if s.trim_start_matches('-').chars().all(|c| c == '0' || c == '.') {
        return "0.0".into();
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    const FOURBAR: &str = include_str!("../../templates/fourbar-chebyshev.toml");

    #[test]
    fn a_field_change_touches_one_value() {
        let out = set(FOURBAR, "f.toml", &[("l_bc".into(), "0.2".into())]).unwrap();
        assert_eq!(out, FOURBAR.replace("l_bc = 0.10", "l_bc = 0.2"));
        let out =
            set(FOURBAR, "f.toml", &[("c[0]".into(), "0.09".into()), ("dynamics.m3".into(), "0.2".into())]).unwrap();
        assert_eq!(out, FOURBAR.replace("c = [0.08, 0.0]", "c = [0.09, 0.0]").replace("m3 = 0.125 ", "m3 = 0.2 "));
        // Every comment is still there.
        let comments = |t: &str| t.lines().filter(|l| l.contains('#')).count();
        assert_eq!(comments(&out), comments(FOURBAR));
    }

    #[test]
    fn refused_changes_give_the_command_lines_messages() {
        let e = set(FOURBAR, "f.toml", &[("l1[2]".into(), "1".into())]).unwrap_err().to_string();
        assert!(e.starts_with("--set l1[2]=1: "), "{e}");
        let e = set("l = = 1\n", "f.toml", &[]).unwrap_err().to_string();
        assert!(e.starts_with("f.toml: not valid TOML: ") && e.contains("line 1"), "{e}");
    }

    #[test]
    fn numbers_are_written_as_floats_on_the_grid() {
        assert_eq!(number(0.09000000000000001, 4), "0.09");
        assert_eq!(number(1.0, 3), "1.0");
        assert_eq!(number(-12.5, 1), "-12.5");
        assert_eq!(number(-0.00001, 3), "0.0");
        assert_eq!(number(120.0, 0), "120.0");
    }
}
