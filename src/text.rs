//! Short quotes of user text in messages: a scene field, a name or an expression can be
//! a megabyte long, and a message quotes at most [`QUOTE_CHARS`] characters of it.

/// `n` and its noun as English writes it, for messages and pages: `1 driver`, `2 drivers`,
/// `0 degrees of freedom`.
///
/// ```
/// use mechdraw::text::counted;
/// assert_eq!(counted(1, "driver", "drivers"), "1 driver");
/// assert_eq!(counted(0, "degree of freedom", "degrees of freedom"), "0 degrees of freedom");
/// ```
pub fn counted(n: impl Into<i64>, one: &str, many: &str) -> String {
    let n = n.into();
    format!("{n} {}", if n == 1 { one } else { many })
}

/// Most characters of user text a message quotes.
pub const QUOTE_CHARS: usize = 80;

/// `text` whole when it has at most [`QUOTE_CHARS`] characters, else its first ones
/// followed by `…` and how many characters it has in all.
///
/// ```
/// use mechdraw::text::excerpt;
/// assert_eq!(excerpt("crank"), "crank");
/// let long = "x".repeat(1000);
/// assert_eq!(excerpt(&long), format!("{}… (1000 characters)", "x".repeat(77)));
/// ```
pub fn excerpt(text: &str) -> String {
    let n = text.chars().count();
    if n <= QUOTE_CHARS {
        return text.to_string();
    }
    let head: String = text.chars().take(QUOTE_CHARS - 3).collect();
    format!("{head}… ({n} characters)")
}

/// The part of `text` (at most [`QUOTE_CHARS`] characters) around the 1-based character
/// `column`, with `…` where it was cut, and the column of the same character in the part.
///
/// ```
/// use mechdraw::text::window;
/// assert_eq!(window("2*t + 1", 3), ("2*t + 1".to_string(), 3));
/// let long = format!("{}t{}", "(".repeat(500), ")".repeat(500));
/// let (part, col) = window(&long, 501);
/// assert!(part.chars().count() <= 80 && part.chars().nth(col - 1) == Some('t'));
/// ```
pub fn window(text: &str, column: usize) -> (String, usize) {
    let chars: Vec<char> = text.chars().collect();
    if chars.len() <= QUOTE_CHARS {
        return (text.to_string(), column);
    }
    // Room for the two ellipses; the column in the middle where the text allows.
    let room = QUOTE_CHARS - 2;
    let at = column.saturating_sub(1).min(chars.len());
    let start = at.saturating_sub(room / 2).min(chars.len().saturating_sub(room));
    let end = (start + room).min(chars.len());
    let mut part = String::new();
    let mut col = at - start + 1;
    if start > 0 {
        part.push('…');
        col += 1;
    }
    part.extend(&chars[start..end]);
    if end < chars.len() {
        part.push('…');
    }
    (part, col)
}

/// The first word of `text` that is how Rust writes a number that is not finite: `NaN` or
/// `inf` (also `-inf`, `+inf`, `infinity`), standing alone (not inside a longer word such as
/// `info` or `inflection`).
///
/// ```
/// use mechdraw::text::non_finite_word;
/// assert_eq!(non_finite_word("|R_A| = inf N"), Some("inf"));
/// assert_eq!(non_finite_word("Me1,NaN,3"), Some("NaN"));
/// assert_eq!(non_finite_word("information; 1e300 N"), None);
/// ```
pub fn non_finite_word(text: &str) -> Option<&str> {
    let word = |c: char| c.is_alphanumeric() || c == '_';
    text.split(|c: char| !word(c))
        .find(|w| matches!(*w, "NaN" | "nan" | "inf" | "infinity" | "Infinity" | "INF" | "NAN"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_window_keeps_the_column_on_its_character_at_either_end() {
        let text: String = (0..300).map(|i| char::from(b'a' + (i % 26) as u8)).collect();
        for column in [1, 2, 40, 150, 299, 300, 301] {
            let (part, col) = window(&text, column);
            assert!(part.chars().count() <= QUOTE_CHARS, "{column}: {part}");
            // Column 301 is just past the end (a missing `)`): the caret after the last character.
            let want = text.chars().nth(column - 1);
            assert_eq!(part.chars().nth(col - 1), want, "{column}: {part} at {col}");
        }
    }
}
