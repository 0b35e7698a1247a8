//! The layout's rules, checked on the source of every crate of the workspace: no import cycle
//! between the modules of a crate (each `.rs` file is a module; a file that names
//! `crate::a::b` imports the module file that holds `a::b`), no source file over 650 lines and
//! no function over 130 lines (`docs/architecture.md`).
//!
//! Code inside `#[cfg(test)]` modules is left out: a unit test may use a module that uses its
//! own.

mod support;

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

const CRATES: [&str; 6] = [
    "src",
    "crates/bem-core/src",
    "crates/face-prep/src",
    "crates/viewer/src",
    "crates/cli/src",
    "crates/tools/src",
];

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The module path of a file relative to its crate's `src` (`settle/mod.rs` → `settle`,
/// `copy/remesh/rounds.rs` → `copy::remesh::rounds`, `lib.rs` → ``).
fn module_of(src: &Path, file: &Path) -> String {
    let rel = file.strip_prefix(src).unwrap().with_extension("");
    let mut parts: Vec<String> = rel
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if matches!(
        parts.last().map(String::as_str),
        Some("mod" | "lib" | "main")
    ) {
        parts.pop();
    }
    parts.join("::")
}

/// The file's text without `#[cfg(test)]` modules and comments.
fn production_code(text: &str) -> String {
    let mut out = String::new();
    let mut skip_depth: Option<i32> = None;
    let mut depth = 0i32;
    let mut pending_cfg_test = false;
    for line in text.lines() {
        let code = line.split("//").next().unwrap_or_default();
        let trimmed = code.trim();
        if skip_depth.is_none() && trimmed.starts_with("#[cfg(test)]") {
            pending_cfg_test = true;
            continue;
        }
        let opens = code.matches('{').count() as i32;
        let closes = code.matches('}').count() as i32;
        if pending_cfg_test {
            pending_cfg_test = false;
            if trimmed.starts_with("mod ") && opens > 0 {
                skip_depth = Some(depth);
            }
        }
        depth += opens - closes;
        if let Some(d) = skip_depth {
            if depth <= d {
                skip_depth = None;
            }
            continue;
        }
        out.push_str(code);
        out.push('\n');
    }
    out
}

/// The `crate::…` paths named in `code`, as lists of segments.
fn crate_paths(code: &str) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let mut rest = code;
    while let Some(i) = rest.find("crate::") {
        let before = rest[..i].chars().last();
        let tail = &rest[i + "crate::".len()..];
        rest = tail;
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
            continue;
        }
        if let Some(group) = tail.strip_prefix('{') {
            // `use crate::{a::b, c};`
            let end = group.find('}').unwrap_or(group.len());
            for item in group[..end].split(',') {
                out.push(segments(item.trim()));
            }
            continue;
        }
        out.push(segments(tail));
    }
    out
}

fn segments(path: &str) -> Vec<String> {
    let mut out = Vec::new();
    for piece in path.split("::") {
        let ident: String = piece
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        if ident.is_empty() {
            break;
        }
        let whole = ident.len() == piece.len();
        out.push(ident);
        if !whole {
            break;
        }
    }
    out
}

/// The import graph of one crate: module → modules it names.
fn graph(src: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let files = support::files_with_extension(src, "rs");
    let modules: BTreeSet<String> = files.iter().map(|f| module_of(src, f)).collect();
    let mut edges = BTreeMap::new();
    for file in &files {
        let from = module_of(src, file);
        let code = production_code(&std::fs::read_to_string(file).unwrap());
        let mut to = BTreeSet::new();
        for path in crate_paths(&code) {
            // The longest prefix of the path that is a module file.
            let target = (1..=path.len())
                .rev()
                .map(|n| path[..n].join("::"))
                .find(|m| modules.contains(m));
            if let Some(t) = target {
                // A file naming its own submodules is the parent declaring them, not a cycle.
                if t != from && !t.starts_with(&format!("{from}::")) && !from.is_empty() {
                    to.insert(t);
                }
            }
        }
        edges.insert(from, to);
    }
    edges
}

/// One cycle of `edges`, if any (depth-first search).
fn find_cycle(edges: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    fn visit(
        node: &str,
        edges: &BTreeMap<String, BTreeSet<String>>,
        state: &mut BTreeMap<String, u8>,
        stack: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        state.insert(node.to_string(), 1);
        stack.push(node.to_string());
        for next in edges.get(node).into_iter().flatten() {
            match state.get(next.as_str()).copied().unwrap_or(0) {
                1 => {
                    let start = stack.iter().position(|n| n == next).unwrap_or(0);
                    let mut cycle = stack[start..].to_vec();
                    cycle.push(next.clone());
                    return Some(cycle);
                }
                0 => {
                    if let Some(c) = visit(next, edges, state, stack) {
                        return Some(c);
                    }
                }
                _ => {}
            }
        }
        stack.pop();
        state.insert(node.to_string(), 2);
        None
    }
    let mut state = BTreeMap::new();
    for node in edges.keys() {
        if state.get(node.as_str()).copied().unwrap_or(0) == 0 {
            let mut stack = Vec::new();
            if let Some(c) = visit(node, edges, &mut state, &mut stack) {
                return Some(c);
            }
        }
    }
    None
}

#[test]
fn no_crate_has_an_import_cycle_between_its_modules() {
    let mut cycles = Vec::new();
    let mut arrows = 0;
    for krate in CRATES {
        let edges = graph(&root().join(krate));
        arrows += edges.values().map(BTreeSet::len).sum::<usize>();
        if let Some(c) = find_cycle(&edges) {
            cycles.push(format!("{krate}: {}", c.join(" -> ")));
        }
    }
    assert!(
        arrows > 100,
        "only {arrows} imports found: is the scanner broken?"
    );
    assert!(cycles.is_empty(), "import cycles:\n{}", cycles.join("\n"));
}

#[test]
fn the_cycle_finder_finds_a_planted_cycle() {
    let mut edges = BTreeMap::new();
    edges.insert("a".to_string(), BTreeSet::from(["b".to_string()]));
    edges.insert("b".to_string(), BTreeSet::from(["c".to_string()]));
    edges.insert("c".to_string(), BTreeSet::from(["a".to_string()]));
    edges.insert("d".to_string(), BTreeSet::new());
    assert_eq!(find_cycle(&edges).map(|c| c.len()), Some(4));
    edges.get_mut("c").unwrap().clear();
    assert_eq!(find_cycle(&edges), None);
    let code = "use crate::{a::b, c};\nfn f() { crate::d::e(); }\n#[cfg(test)]\nmod tests {\n use crate::z;\n}\n";
    let paths = crate_paths(&production_code(code));
    assert_eq!(
        paths,
        vec![vec!["a", "b"], vec!["c"], vec!["d", "e"]]
            .into_iter()
            .map(|p| p.into_iter().map(String::from).collect::<Vec<_>>())
            .collect::<Vec<_>>()
    );
}

#[test]
fn no_source_file_over_650_lines_and_no_function_over_130() {
    let mut long = Vec::new();
    let mut dirs: Vec<PathBuf> = CRATES.iter().map(|c| root().join(c)).collect();
    for extra in [
        "tests",
        "examples",
        "crates/bem-core/tests",
        "crates/face-prep/tests",
        "crates/viewer/tests",
        "crates/cli/tests",
    ] {
        dirs.push(root().join(extra));
    }
    for dir in dirs {
        let files = support::files_with_extension(&dir, "rs");
        for file in files {
            let text = std::fs::read_to_string(&file).unwrap();
            let lines: Vec<&str> = text.lines().collect();
            if lines.len() > 650 {
                long.push(format!("{}: {} lines", file.display(), lines.len()));
            }
            for (i, line) in lines.iter().enumerate() {
                let code = line.trim_start();
                let indent = line.len() - code.len();
                let is_fn = ["fn ", "pub fn ", "pub(crate) fn ", "async fn ", "const fn "]
                    .iter()
                    .any(|p| code.starts_with(p));
                if !is_fn || !line.trim_end().ends_with('{') {
                    continue;
                }
                let close = format!("{}}}", " ".repeat(indent));
                if let Some(len) = lines[i..].iter().position(|l| *l == close)
                    && len > 130
                {
                    long.push(format!(
                        "{}:{}: a {len}-line function",
                        file.display(),
                        i + 1
                    ));
                }
            }
        }
    }
    assert!(long.is_empty(), "too long:\n{}", long.join("\n"));
}
