//! No data lost: killing qmesh (SIGKILL) while it writes leaves the destination holding
//! either the previous file or the complete new one, never a partial file.

use std::process::Command;
use std::time::{Duration, Instant};

fn temp(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("qmesh-kill-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d.join(name)
}

#[test]
fn sigkill_during_write_never_leaves_a_partial_file() {
    let bin = env!("CARGO_BIN_EXE_qmesh");
    let dest = temp("out.vtk");
    let reference = temp("reference.vtk");
    let args = |out: &std::path::Path| {
        vec![
            "generate".to_string(),
            "grid".into(),
            "--size".into(),
            "40".into(),
            "-o".into(),
            out.display().to_string(),
        ]
    };
    // The complete new file, and how long writing it takes.
    let t = Instant::now();
    assert!(Command::new(bin).args(args(&reference)).status().unwrap().success());
    let full = t.elapsed();
    let new = std::fs::read(&reference).unwrap();
    let old = b"previous content\n".to_vec();
    let (mut saw_old, mut saw_new) = (0, 0);
    for i in 0..100u32 {
        std::fs::write(&dest, &old).unwrap();
        let mut child = Command::new(bin).args(args(&dest)).spawn().unwrap();
        // Spread the kills over the whole run (and a little past it).
        std::thread::sleep(full.mul_f64(f64::from(i % 25) / 20.0));
        let _ = child.kill();
        let _ = child.wait();
        let now = std::fs::read(&dest).unwrap();
        if now == old {
            saw_old += 1;
        } else if now == new {
            saw_new += 1;
        } else {
            panic!(
                "kill {i}: the destination holds {} bytes, neither the old file nor the new one ({} bytes)",
                now.len(),
                new.len()
            );
        }
    }
    eprintln!("100 kills: {saw_old} left the previous file, {saw_new} the complete new one");
    // The next successful write sweeps the temporaries the killed runs left behind.
    assert!(Command::new(bin).args(args(&dest)).status().unwrap().success());
    assert_eq!(std::fs::read(&dest).unwrap(), new);
    let left = std::fs::read_dir(dest.parent().unwrap())
        .unwrap()
        .filter(|e| e.as_ref().unwrap().file_name().to_string_lossy().contains("qmesh-tmp"))
        .count();
    assert_eq!(left, 0, "stale temporaries remain");
    assert!(saw_old > 0, "no kill landed before the rename (full run {full:?})");
    assert!(full > Duration::ZERO);
}
