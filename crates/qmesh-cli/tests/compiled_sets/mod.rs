//! `qmesh patterns compile`: a compiled set stands in for its folders everywhere, with
//! the same results, and bad uses are refused in words.

use super::{json_of, qmesh, temp};

#[test]
fn a_compiled_set_gives_what_its_folders_give() {
    let s = |p: &std::path::PathBuf| p.to_str().unwrap().to_string();
    let (folder, set) = (temp("cs-transitions"), temp("cs-transitions.qps"));
    let (tets, box_off, octree) = (temp("cs-t.vtk"), temp("cs-box.off"), temp("cs-oct.vtk"));
    let (from_folder, from_set) = (temp("cs-folder.vtk"), temp("cs-set.vtk"));
    assert_eq!(qmesh(&["patterns", "generate", "transitions", "-o", &s(&folder)]).0, 0);
    let c = json_of(&["patterns", "compile", &s(&folder), "-o", &s(&set), "--json"]);
    assert_eq!(
        (c["f_patterns"].as_u64(), c["v_patterns"].as_u64(), c["skipped"].as_u64()),
        (Some(5), Some(325), Some(0))
    );
    assert_eq!(c["bytes"].as_u64(), Some(std::fs::metadata(&set).unwrap().len()));
    assert_eq!(qmesh(&["generate", "tet-grid", "--size", "2,2,2", "-o", &s(&tets)]).0, 0);
    assert_eq!(qmesh(&["convert", &s(&tets), &s(&box_off)]).0, 0);
    json_of(&["subdivide", &s(&box_off), "--levels", "3", "-o", &s(&octree), "--json"]);
    let a = json_of(&["conformal", &s(&octree), "-o", &s(&from_folder), "--patterns", &s(&folder), "--json"]);
    let b = json_of(&["conformal", &s(&octree), "-o", &s(&from_set), "--patterns", &s(&set), "--json"]);
    assert_eq!(a["cell_types"], b["cell_types"]);
    assert!(a["cell_types"]["pyramid"].as_u64().unwrap() > 0, "{a}");
    assert_eq!(std::fs::read(&from_folder).unwrap(), std::fs::read(&from_set).unwrap());
    // The flags a set was compiled with are the ones it can be used with.
    let (code, _, err) =
        qmesh(&["replace", &s(&octree), &s(&temp("cs-none.vtk")), "--patterns", &s(&set), "--flags", "none"]);
    assert!(code == 2 && err.contains("compiled with corner flags") && err.contains("--flags none"), "{err}");
    // No output from a missing folder; a file that is no compiled set is named as such.
    let nothing = temp("cs-nothing.qps");
    let (code, _, err) = qmesh(&["patterns", "compile", "/nonexistent-folder", "-o", &s(&nothing)]);
    assert!(code == 2 && err.contains("no such pattern folder") && !nothing.exists(), "{err}");
    std::fs::write(&nothing, b"solid nothing\n").unwrap();
    let (code, _, err) = qmesh(&["conformal", &s(&octree), "-o", &s(&from_set), "--force", "--patterns", &s(&nothing)]);
    assert!(code == 2 && err.contains("not a compiled pattern set"), "{err}");
}
