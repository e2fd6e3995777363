//! The binary's shape (ARCHITECTURE.md): no command module of `src/cli/` imports another, and no
//! module of `src/` imports another in a circle. Read from the `use` declarations of the source.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// The modules of `src/cli/` every command may use; the others are commands (and `mod`, the
/// parent that dispatches to them).
const SHARED: [&str; 2] = ["args", "files"];

/// The modules named by one file's `use` declarations among `siblings`: `use super::NAME…`,
/// `use super::{NAME…, …}`, `use crate::cli::NAME…` (for `src/cli/`), `use crate::NAME…`.
fn imports(text: &str, prefixes: &[&str], siblings: &BTreeSet<String>) -> BTreeSet<String> {
    let mut found = BTreeSet::new();
    // Whole declarations, however many lines they take.
    let code: String = text
        .lines()
        .map(|line| line.split("//").next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join(" ");
    for statement in code.split(';') {
        let statement = statement.trim();
        let Some(path) = statement
            .strip_prefix("use ")
            .or_else(|| statement.strip_prefix("pub(crate) use "))
            .or_else(|| statement.strip_prefix("pub use "))
        else {
            continue;
        };
        let path: String = path.chars().filter(|c| !c.is_whitespace()).collect();
        for prefix in prefixes {
            let Some(rest) = path.strip_prefix(prefix) else { continue };
            let heads: Vec<&str> = match rest.strip_prefix('{') {
                Some(list) => top_level_items(list.trim_end_matches('}')),
                None => vec![rest],
            };
            for head in heads {
                let name = head.split("::").next().unwrap_or("");
                if siblings.contains(name) {
                    found.insert(name.to_owned());
                }
            }
        }
    }
    found
}

/// The comma-separated items of a brace list, nested braces kept whole.
fn top_level_items(list: &str) -> Vec<&str> {
    let (mut items, mut depth, mut start) = (Vec::new(), 0, 0);
    for (index, c) in list.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                items.push(&list[start..index]);
                start = index + 1;
            }
            _ => {}
        }
    }
    items.push(&list[start..]);
    items
}

/// The import graph of the `.rs` files of `folder` (module name → modules it imports).
fn graph(folder: &Path, prefixes: &[&str]) -> BTreeMap<String, BTreeSet<String>> {
    let mut files = BTreeMap::new();
    for entry in std::fs::read_dir(folder).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|ext| ext == "rs") {
            let name = path.file_stem().unwrap().to_string_lossy().into_owned();
            files.insert(name, std::fs::read_to_string(&path).unwrap());
        }
    }
    let siblings: BTreeSet<String> = files.keys().cloned().collect();
    files
        .iter()
        .map(|(name, text)| {
            let mut edges = imports(text, prefixes, &siblings);
            edges.remove(name);
            (name.clone(), edges)
        })
        .collect()
}

/// A circle of imports, if any: the modules along it, the first repeated at the end.
fn circle(graph: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    fn visit(
        node: &str,
        graph: &BTreeMap<String, BTreeSet<String>>,
        path: &mut Vec<String>,
        done: &mut BTreeSet<String>,
    ) -> Option<Vec<String>> {
        if let Some(start) = path.iter().position(|n| n == node) {
            let mut found = path[start..].to_vec();
            found.push(node.to_owned());
            return Some(found);
        }
        if done.contains(node) {
            return None;
        }
        path.push(node.to_owned());
        for next in graph.get(node).into_iter().flatten() {
            if let Some(found) = visit(next, graph, path, done) {
                return Some(found);
            }
        }
        path.pop();
        done.insert(node.to_owned());
        None
    }
    let mut done = BTreeSet::new();
    graph.keys().find_map(|node| visit(node, graph, &mut Vec::new(), &mut done))
}

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn no_command_module_imports_another() {
    let graph = graph(&root().join("src/cli"), &["super::", "crate::cli::"]);
    assert!(graph.len() > 10, "src/cli read: {:?}", graph.keys());
    let mut wrong = Vec::new();
    for (module, edges) in &graph {
        if module == "mod" || SHARED.contains(&module.as_str()) {
            continue;
        }
        for target in edges {
            let shared = SHARED.contains(&target.as_str()) || target == "mod";
            if !shared {
                wrong.push(format!("{module} imports {target}"));
            }
        }
    }
    assert!(wrong.is_empty(), "command modules import each other: {wrong:?}");
}

#[test]
fn no_module_of_src_imports_another_in_a_circle() {
    for (folder, prefixes) in
        [("src/cli", &["super::", "crate::cli::"][..]), ("src", &["crate::"][..])]
    {
        let graph = graph(&root().join(folder), prefixes);
        assert_eq!(circle(&graph), None, "a circle of imports in {folder}");
    }
}

#[test]
fn the_reader_of_imports_finds_lists_nested_paths_and_circles() {
    let siblings: BTreeSet<String> =
        ["args", "files", "diag", "view"].iter().map(|s| (*s).to_owned()).collect();
    let text = "use std::io;\nuse super::{\n    args::{A, B},\n    diag::located,\n};\n\
                // use super::view::Hidden;\npub(crate) use crate::cli::files::open;\n";
    let found = imports(text, &["super::", "crate::cli::"], &siblings);
    assert_eq!(found.into_iter().collect::<Vec<_>>(), ["args", "diag", "files"]);
    let mut graph = BTreeMap::new();
    graph.insert("args".to_owned(), BTreeSet::from(["files".to_owned()]));
    graph.insert("files".to_owned(), BTreeSet::from(["diag".to_owned()]));
    graph.insert("diag".to_owned(), BTreeSet::new());
    assert_eq!(circle(&graph), None);
    graph.get_mut("diag").unwrap().insert("args".to_owned());
    assert_eq!(circle(&graph).map(|c| c.len()), Some(4), "args → files → diag → args");
}
