//! Every relative link of README.md and docs/*.md resolves inside the repository (issue 30:
//! the README linked to `../shared/design.md`, outside it): the file exists, and a
//! `#fragment` names a heading of the linked Markdown file (GitHub's anchors).

mod common;

use std::path::{Path, PathBuf};

/// The Markdown files whose links are checked.
fn documents() -> Vec<PathBuf> {
    let root = common::root();
    let mut files = vec![root.join("README.md"), root.join("golden/README.md")];
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root.join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    files.extend(docs);
    files
}

/// The targets of `[text](target)` and `![alt](target)` outside code blocks and code spans.
fn links(markdown: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut fenced = false;
    for line in markdown.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced {
            continue;
        }
        // Drop code spans: `[x](y)` inside backticks is not a link.
        let text: String = line.split('`').step_by(2).collect::<Vec<_>>().join(" ");
        let mut rest = text.as_str();
        while let Some(i) = rest.find("](") {
            let after = &rest[i + 2..];
            let Some(end) = after.find(')') else { break };
            out.push(after[..end].split_whitespace().next().unwrap_or("").to_string());
            rest = &after[end..];
        }
    }
    out
}

/// GitHub's anchor of a heading: lower case, punctuation dropped, spaces to hyphens.
fn anchor(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || *c == ' ' || *c == '-' || *c == '_')
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

fn anchors(markdown: &str) -> Vec<String> {
    let mut fenced = false;
    markdown
        .lines()
        .filter(|l| {
            if l.trim_start().starts_with("```") {
                fenced = !fenced;
            }
            !fenced && l.starts_with('#')
        })
        .map(|l| anchor(l.trim_start_matches('#')))
        .collect()
}

/// What is wrong with `target`, linked from `doc`, if anything.
fn check(doc: &Path, target: &str, root: &Path) -> Option<String> {
    if target.is_empty() || target.contains("://") || target.starts_with("mailto:") {
        return None;
    }
    let (file, fragment) = target.split_once('#').map_or((target, None), |(f, a)| (f, Some(a)));
    let path = if file.is_empty() { doc.to_path_buf() } else { doc.parent().unwrap().join(file) };
    let Ok(resolved) = path.canonicalize() else {
        return Some(format!("{target}: no such file"));
    };
    if !resolved.starts_with(root) {
        return Some(format!("{target}: outside the repository"));
    }
    let fragment = fragment.filter(|a| !a.is_empty())?;
    if resolved.extension().is_some_and(|e| e == "md") {
        let text = std::fs::read_to_string(&resolved).unwrap();
        if !anchors(&text).iter().any(|a| a == fragment) {
            return Some(format!("{target}: no heading #{fragment} in {}", resolved.display()));
        }
    }
    None
}

#[test]
fn every_relative_link_of_the_readme_and_docs_resolves_inside_the_repository() {
    let root = common::root().canonicalize().unwrap();
    let mut broken = Vec::new();
    let mut checked = 0;
    for doc in documents() {
        let text = std::fs::read_to_string(&doc).unwrap();
        for target in links(&text) {
            checked += 1;
            if let Some(why) = check(&doc, &target, &root) {
                broken.push(format!("{}: {why}", doc.strip_prefix(&root).unwrap_or(&doc).display()));
            }
        }
    }
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
    assert!(checked > 40, "only {checked} links found");
}

#[test]
fn the_checker_finds_what_is_broken() {
    let root = common::root().canonicalize().unwrap();
    let readme = root.join("README.md");
    assert_eq!(
        links("see [a](docs/ci.md) and ![p](docs/x.png) `[no](link)`\n```\n[no](x)\n```"),
        ["docs/ci.md", "docs/x.png"]
    );
    assert!(check(&readme, "docs/ci.md", &root).is_none());
    assert!(check(&readme, "docs/ci.md#the-check", &root).is_none());
    assert!(check(&readme, "../shared/design.md", &root).is_some(), "outside the repository");
    assert!(check(&readme, "docs/nothing.md", &root).is_some());
    assert!(check(&readme, "docs/ci.md#no-such-heading", &root).is_some());
    assert!(check(&readme, "https://crates.io/crates/libm", &root).is_none());
    assert_eq!(anchor(" Printed sheets (`--sheets`)"), "printed-sheets---sheets");
}
