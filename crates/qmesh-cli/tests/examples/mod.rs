//! The worked examples of `examples/` (2025 §7.2–7.4, §8), run from their own rule
//! files and meshes, with their counts, and their results compared with what a modeler
//! would have drawn by hand.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::Command;

use qmesh::build::IndexedMesh;
use qmesh::io::{Loaded, read};

use super::{json_of, qmesh, temp};

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples").join(name)
}

/// Runs an example's Python generator (`script args…`), which writes meshes only.
fn generate(script: &Path, args: &[&str]) {
    let out = Command::new("python3")
        .arg(script)
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("python3 is needed to generate {}: {e}", script.display()));
    assert!(out.status.success(), "{}: {}", script.display(), String::from_utf8_lossy(&out.stderr));
}

fn cells(path: &Path) -> IndexedMesh {
    match read(path, None).unwrap_or_else(|e| panic!("{e}")) {
        Loaded::Indexed(mesh) => mesh,
        Loaded::Map(_) => panic!("{}: expected a cell mesh", path.display()),
    }
}

/// The points of a mesh file, rounded to 1e-7, as a set.
fn point_set(path: &Path) -> BTreeSet<[i64; 3]> {
    cells(path).points.iter().map(|p| p.map(|c| (c * 1e7).round() as i64)).collect()
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// 2025 §7.2: a delete then an extend in one call edit all 22 handles (11 doors facing
/// four ways, hinged either side), and the result is the building drawn with the new
/// handles, point for point.
#[test]
fn building_example_replaces_every_handle_in_one_modify_call() {
    let dir = example("building");
    let out = temp("building");
    generate(&dir.join("building.py"), &[s(&out)]);
    let (input, result) = (out.join("building.vtk"), out.join("building_new.vtk"));
    let j = json_of(&["modify", s(&input), s(&result), "--rules", s(&dir.join("handles.toml")), "--json"]);
    let (delete, extend) = (&j["rules"][0], &j["rules"][1]);
    for (r, op) in [(delete, "delete"), (extend, "extend")] {
        assert_eq!(r["op"], op);
        assert_eq!(
            (r["matches"].as_u64(), r["selected"].as_u64(), r["modified"].as_u64()),
            (Some(22), Some(22), Some(22)),
            "{r}"
        );
        assert_eq!((r["automorphisms"].as_u64(), r["valid"].as_bool()), (Some(1), Some(true)), "{r}");
    }
    assert_eq!((delete["volumes_before"].as_u64(), delete["volumes_after"].as_u64()), (Some(1341), Some(1319)));
    assert_eq!((extend["volumes_after"].as_u64(), extend["vertices_created"].as_u64()), (Some(1363), Some(22 * 8)));
    assert_eq!(point_set(&result), point_set(&out.join("building_expected.vtk")));
    // The extend alone finds nothing on the uncut building: M2 only matches cut handles.
    let extend_only = out.join("extend_only.toml");
    let rule = format!(
        "[[rule]]\nop = \"extend\"\nquery = \"{d}/m2.mesh\"\ntarget = \"{d}/m3.mesh\"\nboundary = \"eps\"\nfaces = {{ 1 = \"*\" }}\n",
        d = s(&dir)
    );
    std::fs::write(&extend_only, rule).unwrap();
    let j = json_of(&["modify", s(&input), s(&out.join("unchanged.vtk")), "--rules", s(&extend_only), "--json"]);
    assert_eq!((j["rules"][0]["matches"].as_u64(), j["volumes"].as_u64()), (Some(0), Some(1341)));
}

/// 2025 §8, Fig. 13b: the boot matches in four ways; with the geometric orientation
/// every one of the 16 toe caps lands where it was drawn, on figures turned at random
/// and listed in random order; without it most do not.
#[test]
fn boots_example_puts_every_toe_cap_in_front_only_with_the_geometric_orientation() {
    let dir = example("boots");
    let out = temp("boots");
    generate(&dir.join("boots.py"), &[s(&out)]);
    let input = out.join("figures.vtk");
    let expected = point_set(&out.join("figures_expected.vtk"));
    let mut misplaced = Vec::new();
    for rules in ["boots.toml", "boots-unoriented.toml"] {
        let result = out.join(rules.replace(".toml", ".vtk"));
        let j = json_of(&["modify", s(&input), s(&result), "--rules", s(&dir.join(rules)), "--json"]);
        let r = &j["rules"][0];
        assert_eq!((r["matches"].as_u64(), r["modified"].as_u64()), (Some(16), Some(16)), "{r}");
        assert_eq!((r["automorphisms"].as_u64(), r["valid"].as_bool()), (Some(4), Some(true)), "{r}");
        let got = point_set(&result);
        assert_eq!(got.len(), expected.len());
        misplaced.push(got.difference(&expected).count());
        // The toe caps carry the target's label for them (3); the rest keep theirs.
        let labels = cells(&result).labels;
        let count = |l: i32| labels.iter().filter(|&&x| x == l).count();
        assert_eq!((count(1), count(2), count(3)), (8 * 6, 16 * 2, 16), "labels of {}", result.display());
    }
    assert_eq!(misplaced[0], 0, "geometric orientation: every toe cap where drawn");
    assert!(misplaced[1] >= 4 * 4, "without it, {} toe corners are elsewhere", misplaced[1]);
}

/// 2025 §7.3 and §8, Fig. 13a: an extend then a replace flange every nut of a model of
/// repeated parts (one closed surface each); the look-alike spacers (the nut's mesh
/// topology, another shape) are left alone only with `max_residual`.
#[test]
fn parts_example_flanges_every_nut_and_no_look_alike() {
    let dir = example("parts");
    let out = temp("parts");
    generate(&dir.join("nuts.py"), &[s(&out)]);
    let input = out.join("nuts.vtk");
    let expected = point_set(&out.join("nuts_expected.vtk"));
    for (rules, flanged) in [("nuts.toml", 6), ("nuts-topology-only.toml", 8)] {
        let result = out.join(rules.replace(".toml", "_result.vtk"));
        let j = json_of(&["modify", s(&input), s(&result), "--rules", s(&dir.join(rules)), "--json"]);
        let (glue, merge) = (&j["rules"][0], &j["rules"][1]);
        assert_eq!((glue["op"].as_str(), merge["op"].as_str()), (Some("extend"), Some("replace")));
        assert_eq!((glue["matches"].as_u64(), glue["modified"].as_u64()), (Some(flanged), Some(flanged)), "{glue}");
        assert_eq!(glue["automorphisms"].as_u64(), Some(96), "the nut's mesh is a 12 × 4 torus grid");
        assert_eq!((glue["volumes_after"].as_u64(), glue["valid"].as_bool()), (Some(8 + flanged), Some(true)));
        assert_eq!((merge["modified"].as_u64(), merge["volumes_after"].as_u64()), (Some(flanged), Some(8)));
        assert_eq!(merge["valid"].as_bool(), Some(true));
        let got = point_set(&result);
        // Each flange brings 24 points; with max_residual they are exactly the drawn ones.
        assert_eq!(got.difference(&expected).count(), 24 * (flanged as usize - 6), "{rules}");
        assert!(expected.is_subset(&got), "{rules}: every nut flanged as drawn");
    }
}

#[test]
fn terrain_example_runs_the_papers_two_steps_from_its_rule_files() {
    // 2025 §7.4 on a 16×16 terrain with the rule files and meshes of examples/terrain.
    let example = example("terrain");
    let (t, spots, houses) = (temp("terrain.vtk"), temp("terrain_spots.vtk"), temp("terrain_houses.vtk"));
    let j = json_of(&["generate", "terrain", "--size", "16", "--base", "12", "-o", t.to_str().unwrap(), "--json"]);
    assert_eq!((j["volumes"].as_u64(), j["darts"].as_u64()), (Some(256), Some(256 * 26)));
    let rules = |f: &str| example.join(f).to_str().unwrap().to_string();
    let flatten = rules("flatten.toml");
    let j = json_of(&["modify", t.to_str().unwrap(), spots.to_str().unwrap(), "--rules", &flatten, "--json"]);
    let r = &j["rules"][0];
    assert_eq!(r["op"].as_str(), Some("apply"));
    assert!(r["starts_tested"].as_u64().is_some_and(|n| n > 0 && n <= 256 * 26), "{r}");
    let spots_made = r["modified"].as_u64().unwrap();
    assert!(spots_made >= 5, "only {spots_made} spots on 16×16 voxels");
    assert_eq!(j["volumes"].as_u64(), Some(256 - 8 * spots_made));
    let house_rules = rules("houses.toml");
    let j = json_of(&["modify", spots.to_str().unwrap(), houses.to_str().unwrap(), "--rules", &house_rules, "--json"]);
    let r = &j["rules"][0];
    assert_eq!((r["matches"].as_u64(), r["modified"].as_u64()), (Some(spots_made), Some(spots_made)));
    assert_eq!(j["volumes"].as_u64(), Some(256 - 8 * spots_made + 3 * spots_made));
    assert_eq!(j["valid"], true);
    // `qmesh query` picks at random the way `modify` does, counting every match.
    let block = example.join("block.vtk");
    let (b, t_) = (block.to_str().unwrap(), t.to_str().unwrap());
    let j = json_of(&["query", b, t_, "--strategy", "random", "--seed", "4", "--max", "3", "--json"]);
    assert_eq!((j["queries"][0]["matches"].as_u64(), j["selected"].as_u64()), (Some(14 * 14), Some(3)));
    // Bad terrain options are refused with the option's name.
    let (code, _, err) = qmesh(&["generate", "terrain", "--roughness", "2", "-o", t.to_str().unwrap()]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--roughness must be in (0, 1]"), "{err}");
    let (code, _, err) = qmesh(&["generate", "terrain", "--size", "4,0", "-o", t.to_str().unwrap()]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--size takes N or NX,NY"), "{err}");
}
