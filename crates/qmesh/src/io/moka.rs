//! `.moka` (Moka modeler, ASCII generalized maps) ↔ combinatorial maps; format and
//! conversion rules in `shared/data/patterns/cgal/FORMAT.md`.

use std::io::Write;
use std::path::Path;

use super::error::{IoError, IoResult};
use super::lexer::{Lexer, clip};
use crate::cmap::{CMap3, Dart};
use crate::disjoint_sets::DisjointSets;

struct GDart {
    alpha: [u32; 4],
    /// Mark byte of group 0 as stored (before applying the header's mask).
    mark0: u8,
    point: Option<[f64; 3]>,
}

/// The g-darts and the header's (mask, used) bytes of mark group 0.
fn parse_gdarts(lx: &mut Lexer<'_>) -> IoResult<(Vec<GDart>, u8, u8)> {
    let first = lx.rest_of_line();
    if !first.starts_with("Moka file") {
        return Err(lx.err(format!("expected 'Moka file [ascii]', found '{}'", clip(first))));
    }
    if first.contains("binary") {
        return Err(IoError::unsupported(lx.path(), "binary Moka files are not supported"));
    }
    // Global mark state: (mask, used) for 4 groups of 8 marks; group 0 holds the flags.
    let state: Vec<i64> = lx.rest_of_line().split_whitespace().filter_map(|t| t.parse().ok()).collect();
    let (mask0, used0) = (state.first().copied().unwrap_or(0) as u8, state.get(1).copied().unwrap_or(0) as u8);
    let mut out = Vec::new();
    while lx.remaining() > 0 {
        if lx.peek().is_none() {
            break;
        }
        let mut alpha = [0u32; 4];
        for a in alpha.iter_mut() {
            let v = lx.int("an α index (a g-dart number)")?;
            if v < 0 || v > u32::MAX as i64 {
                return Err(lx.err(format!("g-dart {}: α index {v} is not a g-dart number", out.len())));
            }
            *a = v as u32;
        }
        let mark0 = lx.int("a mark byte (integer)")? as u8;
        for _ in 1..4 {
            lx.int("a mark byte (integer)")?;
        }
        let p: i64 = lx.parse("the point flag (0 or 1)")?;
        let point = match p {
            0 => None,
            1 => Some(lx.point()?),
            _ => return Err(lx.err(format!("expected the point flag 0 or 1, found {p}"))),
        };
        out.push(GDart { alpha, mark0, point });
    }
    Ok((out, mask0, used0))
}

/// Reads a `.moka` file as a combinatorial map (one orientation class per component).
/// The map is a surface map (dimension 2) when some dart is 2-free.
pub fn read(path: &Path, data: &[u8]) -> IoResult<CMap3> {
    read_with_flags(path, data).map(|(m, _)| m)
}

/// As [`read`], also returning the darts whose g-dart carries an effective Moka mark in
/// group 0 (`(byte XOR mask) & used ≠ 0`): the flags stored in the file, if any.
pub fn read_with_flags(path: &Path, data: &[u8]) -> IoResult<(CMap3, Vec<Dart>)> {
    let mut lx = Lexer::new(path, data, None);
    let (g, mask0, used0) = parse_gdarts(&mut lx)?;
    let n = g.len();
    if n == 0 {
        return Err(lx.err("expected at least one g-dart line"));
    }
    let bad = |msg: String| IoError::Unsupported { path: path.into(), msg };
    for (k, d) in g.iter().enumerate() {
        for i in 0..4 {
            let a = d.alpha[i] as usize;
            if a >= n {
                return Err(bad(format!("g-dart {k}: α{i} = {a} is out of range (the file has {n} g-darts)")));
            }
            if g[a].alpha[i] as usize != k {
                return Err(bad(format!("g-dart {k}: α{i} is not an involution (α{i}(α{i}({k})) ≠ {k})")));
            }
        }
        if d.alpha[0] as usize == k {
            return Err(bad(format!("g-dart {k}: α0 is free")));
        }
    }
    // Orientation classes: 1 = kept, 2 = its α0 twin.
    let mut class = vec![0u8; n];
    let mut stack = Vec::new();
    for s in 0..n {
        if class[s] != 0 {
            continue;
        }
        class[s] = 1;
        class[g[s].alpha[0] as usize] = 2;
        stack.push(s as u32);
        while let Some(d) = stack.pop() {
            let d = d as usize;
            let a0 = g[d].alpha[0] as usize;
            for i in 1..4 {
                // αi∘α0 and α0∘αi stay in the class (skipping free αi).
                let (ai_a0, ai_d) = (g[a0].alpha[i] as usize, g[d].alpha[i] as usize);
                let via_twin = (ai_a0 != a0).then_some(ai_a0);
                let via_self = (ai_d != d).then(|| g[ai_d].alpha[0] as usize);
                for e in [via_twin, via_self].into_iter().flatten() {
                    match class[e] {
                        0 => {
                            class[e] = 1;
                            class[g[e].alpha[0] as usize] = 2;
                            stack.push(e as u32);
                        }
                        2 => {
                            return Err(bad(format!("the generalized map is not orientable (g-dart {e})")));
                        }
                        _ => {}
                    }
                }
            }
        }
    }
    // Vertex orbits ⟨α1, α2, α3⟩.
    let mut orbits = DisjointSets::new(n);
    for (k, d) in g.iter().enumerate() {
        for i in 1..4 {
            orbits.union(k as u32, d.alpha[i]);
        }
    }
    let mut map = CMap3::with_capacity(n / 2, n / 8);
    let mut vid = vec![u32::MAX; n];
    for (k, d) in g.iter().enumerate() {
        if let Some(p) = d.point {
            let r = orbits.find(k as u32) as usize;
            if vid[r] == u32::MAX {
                vid[r] = map.add_vertex(p);
            }
        }
    }
    let mut dart_of = vec![0u32; n];
    for k in 0..n {
        if class[k] == 1 {
            let r = orbits.find(k as u32) as usize;
            if vid[r] == u32::MAX {
                return Err(bad(format!("the vertex of g-dart {k} has no point")));
            }
            dart_of[k] = map.create_dart(vid[r]).raw();
        }
    }
    let mut two_free = false;
    for k in 0..n {
        if class[k] != 1 {
            continue;
        }
        let d = Dart::from_raw(dart_of[k]).expect("kept darts exist");
        let a0 = g[k].alpha[0] as usize;
        for i in 1..4 {
            let e = g[a0].alpha[i] as usize;
            if e == a0 {
                two_free |= i == 2;
                continue;
            }
            let t = Dart::from_raw(dart_of[e]).ok_or_else(|| bad(format!("g-dart {e} should be kept")))?;
            map.link(d, i, t);
        }
    }
    if two_free {
        map.set_dimension(2);
    }
    let flagged = (0..n)
        .filter(|&k| class[k] == 1 && (g[k].mark0 ^ mask0) & used0 != 0)
        .filter_map(|k| Dart::from_raw(dart_of[k]))
        .collect();
    Ok((map, flagged))
}

/// Writes a map as a `.moka` generalized map: dart k → g-darts 2k, 2k+1; the darts
/// of `flags` carry Moka mark 0 (the papers' pattern flags).
pub fn write(path: &Path, map: &CMap3, flags: Option<crate::cmap::Mark>, w: &mut dyn Write) -> IoResult<()> {
    let io = |e| IoError::io(path, e);
    let mut index = vec![u32::MAX; map.dart_capacity()];
    let darts: Vec<Dart> = map.darts().collect();
    for (k, d) in darts.iter().enumerate() {
        index[d.idx()] = k as u32;
    }
    let gi = |d: Option<Dart>| d.map(|d| index[d.idx()]);
    let mut has_point = vec![false; map.nb_vertex_ids()];
    let used = u8::from(flags.is_some());
    writeln!(w, "Moka file [ascii]\n0 {used} 0 0 0 0 0 0 ").map_err(io)?;
    for (k, &d) in darts.iter().enumerate() {
        let (a, b) = (2 * k as u32, 2 * k as u32 + 1);
        let prev = gi(map.beta(d, 0)).map_or(a, |p| 2 * p + 1);
        let next = gi(map.beta(d, 1)).map_or(b, |p| 2 * p);
        let o2 = gi(map.beta(d, 2));
        let o3 = gi(map.beta(d, 3));
        let v = map.vertex_of(d) as usize;
        let point = if has_point[v] { None } else { Some(map.position(v as u32)) };
        has_point[v] = true;
        let p = point.map_or("0".to_string(), |p| format!("1\t{}\t{}\t{}", p[0], p[1], p[2]));
        let (a2, b2) = o2.map_or((a, b), |m| (2 * m + 1, 2 * m));
        let (a3, b3) = o3.map_or((a, b), |m| (2 * m + 1, 2 * m));
        let m = u8::from(flags.is_some_and(|f| map.is_marked(d, f)));
        writeln!(w, "{b}\t{prev}\t{a2}\t{a3}\t{m}\t0\t0\t0\t{p}").map_err(io)?;
        writeln!(w, "{a}\t{next}\t{b2}\t{b3}\t0\t0\t0\t0\t0").map_err(io)?;
    }
    Ok(())
}
