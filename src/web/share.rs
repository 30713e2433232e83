//! The share link: a whole scene in a URL fragment, `#scene=v1.<data>`, that opens to the
//! same picture in any copy of the page, offline and from `file://` (the fragment never
//! leaves the browser).
//!
//! `<data>` is the scene's text (UTF-8) deflated with zlib — whose Adler-32 checksum makes a
//! link cut short or changed in transit fail to open instead of opening as another scene —
//! in URL-safe base64 without padding. `v1` is the format: a page refuses a link of a format
//! it does not know by saying which one it is, so a link from a newer mechdraw is named as
//! such rather than read wrongly.

use base64::Engine;
use base64::engine::general_purpose::URL_SAFE_NO_PAD;

/// The format this build writes and reads.
pub const FORMAT: &str = "v1";

/// Largest scene a link opens, bytes (a scene is a few KB; this stops a crafted link from
/// inflating to gigabytes).
pub const MAX_SCENE_BYTES: usize = 1 << 20;

/// Why a share link does not open.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ShareError {
    /// No `v1.` (or other format) prefix. Example: `#scene=abc`.
    #[error("the share link is not a mechdraw scene link (it should read #scene=v1.…)")]
    NotALink,
    /// A format this build does not read. Example: `#scene=v2.…`.
    #[error(
        "the share link is in format {0}, from a newer mechdraw; this page reads {FORMAT}: open it with a newer page, or ask for the .toml file"
    )]
    Newer(String),
    /// The data is not base64, does not inflate, or fails its checksum. Example: a link cut
    /// short by a mail program.
    #[error("the share link is cut short or damaged ({0}): copy the whole link again")]
    Damaged(String),
    /// It inflates to something that is not UTF-8 text.
    #[error("the share link does not hold a scene's text")]
    NotText,
}

/// The fragment's value for `text`: `v1.<base64url(zlib(text))>`.
pub fn encode(text: &str) -> String {
    let packed = miniz_oxide::deflate::compress_to_vec_zlib(text.as_bytes(), 9);
    format!("{FORMAT}.{}", URL_SAFE_NO_PAD.encode(packed))
}

/// The scene's text in a fragment's value made by [`encode`] (or by a newer mechdraw, which
/// is refused by name).
pub fn decode(link: &str) -> Result<String, ShareError> {
    let (format, data) = link.trim().split_once('.').ok_or(ShareError::NotALink)?;
    if format != FORMAT {
        let newer = format.strip_prefix('v').is_some_and(|n| !n.is_empty() && n.chars().all(|c| c.is_ascii_digit()));
        return Err(if newer { ShareError::Newer(format.to_string()) } else { ShareError::NotALink });
    }
    let packed = URL_SAFE_NO_PAD
        .decode(data.trim_end_matches('='))
        .map_err(|e| ShareError::Damaged(format!("not base64: {e}")))?;
    let bytes = miniz_oxide::inflate::decompress_to_vec_zlib_with_limit(&packed, MAX_SCENE_BYTES)
        .map_err(|e| ShareError::Damaged(format!("{:?}", e.status)))?;
    String::from_utf8(bytes).map_err(|_| ShareError::NotText)
}

#[cfg(test)]
mod tests {
    use super::*;

    const SCENE: &str = include_str!("../../templates/fourbar-chebyshev.toml");

    #[test]
    fn a_scene_comes_back_byte_for_byte_and_small() {
        let link = encode(SCENE);
        assert!(link.starts_with("v1.") && link.len() < SCENE.len(), "{} for {} bytes", link.len(), SCENE.len());
        assert!(link.bytes().all(|b| b.is_ascii_alphanumeric() || b"-_.".contains(&b)), "URL-safe: {link}");
        assert_eq!(decode(&link).unwrap(), SCENE);
    }

    #[test]
    fn a_cut_changed_or_newer_link_is_refused_by_name() {
        let link = encode(SCENE);
        for cut in [link.len() - 1, link.len() - 7, link.len() / 2, 4] {
            assert!(matches!(decode(&link[..cut]), Err(ShareError::Damaged(_))), "cut at {cut}");
        }
        // One character changed anywhere in the data: the checksum (or inflate) catches it.
        for i in (3..link.len()).step_by(17) {
            let mut b = link.clone().into_bytes();
            b[i] = if b[i] == b'A' { b'B' } else { b'A' };
            let changed = String::from_utf8(b).unwrap();
            assert!(decode(&changed).is_err(), "a change at {i} went through");
        }
        assert_eq!(decode(&link.replacen("v1.", "v2.", 1)), Err(ShareError::Newer("v2".into())));
        assert!(decode(&link.replacen("v1.", "v2.", 1)).unwrap_err().to_string().contains("newer mechdraw"));
        assert_eq!(decode("hello"), Err(ShareError::NotALink));
        assert!(matches!(decode("v1.@@@"), Err(ShareError::Damaged(_))));
        let not_text =
            format!("v1.{}", URL_SAFE_NO_PAD.encode(miniz_oxide::deflate::compress_to_vec_zlib(&[0xff, 0xfe], 9)));
        assert_eq!(decode(&not_text), Err(ShareError::NotText));
    }
}
