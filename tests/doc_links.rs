//! The README and every document under `docs/` link only to files that exist, the README stays a
//! five-minute read (at most 250 lines), and no document points outside the repository.

mod support;

use std::path::{Path, PathBuf};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// README.md and every `.md` file under `docs/`.
fn documents() -> Vec<PathBuf> {
    let mut out = vec![root().join("README.md")];
    out.extend(support::files_with_extension(&root().join("docs"), "md"));
    out
}

/// The targets of the Markdown links `[text](target)` and images `![alt](target)` in `text`,
/// outside code blocks and inline code.
fn link_targets(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut in_fence = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            in_fence = !in_fence;
            continue;
        }
        if in_fence {
            continue;
        }
        // Drop inline code spans.
        let prose: String = line
            .split('`')
            .enumerate()
            .filter(|(i, _)| i % 2 == 0)
            .map(|(_, s)| s)
            .collect::<Vec<_>>()
            .join(" ");
        let mut rest = prose.as_str();
        while let Some(i) = rest.find("](") {
            let after = &rest[i + 2..];
            let Some(end) = after.find(')') else { break };
            out.push(after[..end].trim().to_string());
            rest = &after[end..];
        }
    }
    out
}

#[test]
fn every_relative_link_in_the_readme_and_docs_resolves() {
    let docs = documents();
    assert!(docs.len() >= 5, "found only {} documents", docs.len());
    let mut checked = 0;
    let mut broken = Vec::new();
    for doc in &docs {
        let text = std::fs::read_to_string(doc).unwrap();
        for target in link_targets(&text) {
            if target.starts_with("http://")
                || target.starts_with("https://")
                || target.starts_with("mailto:")
                || target.starts_with('#')
            {
                continue;
            }
            let file = target.split('#').next().unwrap_or_default();
            let resolved = doc.parent().unwrap().join(file);
            checked += 1;
            if !resolved.exists() {
                broken.push(format!("{}: {target}", doc.display()));
            }
        }
    }
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
    assert!(checked >= 20, "only {checked} relative links checked");
}

#[test]
fn the_readme_is_at_most_250_lines() {
    let lines = std::fs::read_to_string(root().join("README.md"))
        .unwrap()
        .lines()
        .count();
    assert!(lines <= 250, "README.md has {lines} lines");
}

#[test]
fn no_document_points_outside_the_repository() {
    for doc in documents() {
        let text = std::fs::read_to_string(&doc).unwrap();
        for needle in ["../shared", "/work/", "DESIGN.md"] {
            assert!(
                !text.contains(needle),
                "{} mentions {needle}",
                doc.display()
            );
        }
    }
}

#[test]
fn the_link_scanner_finds_links_and_skips_code() {
    let text = "see [a](x.md) and ![b](img/y.png#top)\n`[c](not.md)`\n```\n[d](no.md)\n```\n";
    assert_eq!(link_targets(text), vec!["x.md", "img/y.png#top"]);
}
