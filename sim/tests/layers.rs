//! The library's modules form layers (`sim/src/lib.rs`): a module uses only
//! modules of its own layer or of the layers before it, and no two files
//! use each other, directly or around a loop. Read from the sources: every
//! `crate::…` path (outside comments) names the module it uses.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// The top-level modules, by layer (`sim/src/lib.rs`).
const LAYERS: [&[&str]; 6] = [&["config", "formats", "blocks", "rng"], &["drive"], &["hdl"], &["budget"], &["eval", "error"], &["jobs"]];

fn layer(module: &str) -> usize {
    let top = module.split("::").next().unwrap_or("");
    LAYERS.iter().position(|l| l.contains(&top)).unwrap_or_else(|| panic!("module {module} is in no layer of LAYERS"))
}

/// Module path → source text, for every file under `sim/src` but `lib.rs`.
fn sources() -> BTreeMap<String, String> {
    fn walk(dir: &Path, root: &Path, out: &mut BTreeMap<String, String>) {
        for e in std::fs::read_dir(dir).expect("sim/src reads") {
            let p = e.expect("an entry").path();
            if p.is_dir() {
                walk(&p, root, out);
            } else if p.extension().is_some_and(|x| x == "rs") {
                let rel = p.strip_prefix(root).expect("under src").with_extension("");
                let mut m = rel.to_string_lossy().replace('/', "::");
                if let Some(parent) = m.strip_suffix("::mod") {
                    m = parent.to_string();
                }
                if m != "lib" {
                    let text = std::fs::read_to_string(&p).expect("a source reads");
                    out.insert(m, text);
                }
            }
        }
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut out = BTreeMap::new();
    walk(&root, &root, &mut out);
    out
}

/// The modules `text` (the file of `module`) uses: the longest known module
/// prefix of each `crate::a::b::…` path, and each name of `crate::{a, b}`.
fn uses(module: &str, text: &str, known: &BTreeSet<String>) -> BTreeSet<String> {
    let code: String = text.lines().map(|l| l.split("//").next().unwrap_or("")).collect::<Vec<_>>().join("\n");
    let mut out = BTreeSet::new();
    let mut rest = code.as_str();
    while let Some(i) = rest.find("crate::") {
        rest = &rest[i + "crate::".len()..];
        let names: Vec<&str> = if let Some(group) = rest.strip_prefix('{') {
            group.split('}').next().unwrap_or("").split(',').map(|n| n.trim().split("::").next().unwrap_or("")).collect()
        } else {
            let path: String = rest.chars().take_while(|c| c.is_alphanumeric() || *c == '_' || *c == ':').collect();
            let parts: Vec<&str> = path.split("::").collect();
            (1..=parts.len())
                .rev()
                .map(|k| parts[..k].join("::"))
                .find(|m| known.contains(m))
                .map(|m| vec![Box::leak(m.into_boxed_str()) as &str])
                .unwrap_or_default()
        };
        out.extend(names.into_iter().filter(|n| known.contains(*n) && *n != module).map(str::to_string));
    }
    out
}

fn graph() -> BTreeMap<String, BTreeSet<String>> {
    let src = sources();
    let known: BTreeSet<String> = src.keys().cloned().collect();
    src.iter().map(|(m, t)| (m.clone(), uses(m, t, &known))).collect()
}

#[test]
fn every_module_uses_only_its_own_layer_and_those_before_it() {
    let g = graph();
    assert!(g.len() > 20, "the sources were found: {:?}", g.keys());
    let mut wrong = Vec::new();
    for (m, used) in &g {
        for u in used {
            if layer(u) > layer(m) {
                wrong.push(format!("{m} (layer {}) uses {u} (layer {})", layer(m) + 1, layer(u) + 1));
            }
        }
    }
    assert!(wrong.is_empty(), "modules reaching up a layer:\n{}", wrong.join("\n"));
}

#[test]
fn no_file_of_the_library_depends_on_itself_around_a_loop() {
    let g = graph();
    // Depth-first search for a back edge; `path` is the stack of the search.
    fn visit<'a>(m: &'a str, g: &'a BTreeMap<String, BTreeSet<String>>, state: &mut BTreeMap<&'a str, bool>, path: &mut Vec<&'a str>) -> Option<Vec<String>> {
        state.insert(m, true);
        path.push(m);
        for u in &g[m] {
            match state.get(u.as_str()) {
                Some(true) => {
                    let at = path.iter().position(|p| p == u).expect("on the stack");
                    return Some(path[at..].iter().map(|s| s.to_string()).chain([u.clone()]).collect());
                }
                Some(false) => {}
                None => {
                    if let Some(c) = visit(u, g, state, path) {
                        return Some(c);
                    }
                }
            }
        }
        path.pop();
        state.insert(m, false);
        None
    }
    let mut state = BTreeMap::new();
    for m in g.keys() {
        if !state.contains_key(m.as_str()) {
            let cycle = visit(m, &g, &mut state, &mut Vec::new());
            assert!(cycle.is_none(), "an import cycle: {}", cycle.unwrap_or_default().join(" -> "));
        }
    }
}
