//! A bounding-volume hierarchy over the triangles of a surface: which boxes the surface
//! touches (octree refinement, 2022 §7.1) and the data the winding number needs.

use smallvec::{SmallVec, smallvec};

use super::{cross, sub};

/// Axis-aligned box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub lo: [f64; 3],
    pub hi: [f64; 3],
}

impl Aabb {
    pub const EMPTY: Aabb = Aabb { lo: [f64::INFINITY; 3], hi: [f64::NEG_INFINITY; 3] };

    pub fn add(&mut self, p: [f64; 3]) {
        for (k, &x) in p.iter().enumerate() {
            self.lo[k] = self.lo[k].min(x);
            self.hi[k] = self.hi[k].max(x);
        }
    }

    pub fn of(points: impl IntoIterator<Item = [f64; 3]>) -> Aabb {
        let mut b = Aabb::EMPTY;
        points.into_iter().for_each(|p| b.add(p));
        b
    }

    pub fn overlaps(&self, o: &Aabb) -> bool {
        (0..3).all(|k| self.lo[k] <= o.hi[k] && o.lo[k] <= self.hi[k])
    }

    pub fn centre(&self) -> [f64; 3] {
        [0, 1, 2].map(|k| 0.5 * (self.lo[k] + self.hi[k]))
    }

    pub fn extent(&self) -> [f64; 3] {
        [0, 1, 2].map(|k| self.hi[k] - self.lo[k])
    }
}

/// One node: its box, its triangles `start..start + count` when a leaf (count > 0),
/// else its children `left` and `left + 1`; plus the far-field data of its triangles.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Node {
    pub bounds: Aabb,
    pub start: u32,
    pub count: u32,
    pub left: u32,
    /// Sum of the triangles' area vectors (½ (b − a) × (c − a)).
    pub area_normal: [f64; 3],
    /// Area-weighted centroid of the triangles.
    pub centre: [f64; 3],
    /// Largest distance from `centre` to the node's box.
    pub radius: f64,
}

/// Triangles in BVH order with their tree.
#[derive(Clone, Debug)]
pub struct TriangleBvh {
    pub(crate) triangles: Vec<[[f64; 3]; 3]>,
    pub(crate) nodes: Vec<Node>,
}

const LEAF_SIZE: usize = 4;

fn area_vector(t: &[[f64; 3]; 3]) -> [f64; 3] {
    cross(sub(t[1], t[0]), sub(t[2], t[0])).map(|c| 0.5 * c)
}

impl TriangleBvh {
    /// Builds the tree (median split on the longest axis of the centroids). The split
    /// moves triangle indices over centroids computed once; the far-field data of inner
    /// nodes are merged from their children's.
    pub fn new(triangles: Vec<[[f64; 3]; 3]>) -> TriangleBvh {
        let n = triangles.len();
        let centroids: Vec<[f64; 3]> = triangles.iter().map(tri_centroid).collect();
        let mut order: Vec<u32> = (0..n as u32).collect();
        let mut nodes = Vec::with_capacity(2 * n / LEAF_SIZE + 1);
        let span = |start: usize, count: usize| Node {
            bounds: Aabb::EMPTY,
            start: start as u32,
            count: count as u32,
            left: 0,
            area_normal: [0.0; 3],
            centre: [0.0; 3],
            radius: 0.0,
        };
        if n > 0 {
            nodes.push(span(0, n));
            let mut stack = vec![0usize];
            while let Some(i) = stack.pop() {
                let (start, count) = (nodes[i].start as usize, nodes[i].count as usize);
                if count <= LEAF_SIZE {
                    continue;
                }
                let slice = &mut order[start..start + count];
                let cb = Aabb::of(slice.iter().map(|&t| centroids[t as usize]));
                let e = cb.extent();
                let axis = (0..3).max_by(|&a, &b| e[a].total_cmp(&e[b])).unwrap_or(0);
                let mid = count / 2;
                slice.select_nth_unstable_by(mid, |&a, &b| {
                    centroids[a as usize][axis].total_cmp(&centroids[b as usize][axis])
                });
                let left = nodes.len();
                nodes.push(span(start, mid));
                nodes.push(span(start + mid, count - mid));
                nodes[i].count = 0;
                nodes[i].left = left as u32;
                stack.extend([left, left + 1]);
            }
        }
        let triangles: Vec<[[f64; 3]; 3]> = order.iter().map(|&t| triangles[t as usize]).collect();
        // Children come after their parent: fill the nodes from the last one.
        let mut sums = vec![([0.0; 3], 0.0); nodes.len()]; // area-weighted centroid sum, area
        for i in (0..nodes.len()).rev() {
            let node = nodes[i];
            let (bounds, an, weighted, area) = if node.count > 0 {
                let tris = &triangles[node.start as usize..(node.start + node.count) as usize];
                let (mut an, mut weighted, mut area) = ([0.0; 3], [0.0; 3], 0.0);
                for t in tris {
                    let a = area_vector(t);
                    let w = super::dot(a, a).sqrt();
                    let c = tri_centroid(t);
                    for k in 0..3 {
                        an[k] += a[k];
                        weighted[k] += w * c[k];
                    }
                    area += w;
                }
                (Aabb::of(tris.iter().flatten().copied()), an, weighted, area)
            } else {
                let (l, r) = (node.left as usize, node.left as usize + 1);
                let (a, b) = (&nodes[l], &nodes[r]);
                let bounds = Aabb {
                    lo: [0, 1, 2].map(|k| a.bounds.lo[k].min(b.bounds.lo[k])),
                    hi: [0, 1, 2].map(|k| a.bounds.hi[k].max(b.bounds.hi[k])),
                };
                let an = [0, 1, 2].map(|k| a.area_normal[k] + b.area_normal[k]);
                let weighted = [0, 1, 2].map(|k| sums[l].0[k] + sums[r].0[k]);
                (bounds, an, weighted, sums[l].1 + sums[r].1)
            };
            sums[i] = (weighted, area);
            let centre = if area > 0.0 { weighted.map(|c| c / area) } else { bounds.centre() };
            let radius = (0..8)
                .map(|c| {
                    let p = [0, 1, 2].map(|k| if c >> k & 1 == 0 { bounds.lo[k] } else { bounds.hi[k] });
                    let d = sub(p, centre);
                    super::dot(d, d).sqrt()
                })
                .fold(0.0, f64::max);
            nodes[i] = Node { bounds, area_normal: an, centre, radius, ..node };
        }
        TriangleBvh { triangles, nodes }
    }

    /// Triangles of a polygon surface (polygons fanned from their first vertex).
    pub fn from_polygons<'a>(points: &[[f64; 3]], polygons: impl IntoIterator<Item = &'a [u32]>) -> TriangleBvh {
        let mut tris = Vec::new();
        for poly in polygons {
            for k in 1..poly.len().saturating_sub(1) {
                tris.push([poly[0], poly[k], poly[k + 1]].map(|v| points[v as usize]));
            }
        }
        TriangleBvh::new(tris)
    }

    pub fn len(&self) -> usize {
        self.triangles.len()
    }

    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// Bounding box of all triangles.
    pub fn bounds(&self) -> Aabb {
        self.nodes.first().map_or(Aabb::EMPTY, |n| n.bounds)
    }

    /// Whether some triangle touches the closed box `b` (separating-axis test, with the
    /// box grown by 10⁻¹⁰ of its size so that touching counts as intersecting: a
    /// refinement decision errs toward refining).
    pub fn intersects_box(&self, b: &Aabb) -> bool {
        self.intersects_box_near(b, None)
    }

    /// [`intersects_box`](Self::intersects_box), looking only at the leaves of `near`
    /// when given: the leaves [`leaves_near`](Self::leaves_near) lists for a box that
    /// contains `b` (an octree cell's parent), which hold every leaf whose triangles
    /// the test could reach. The answer is the same.
    pub fn intersects_box_near(&self, b: &Aabb, near: Option<&[u32]>) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let (c, h, grown) = touch_box(b);
        let leaf_touches = |n: &Node| {
            let tris = &self.triangles[n.start as usize..(n.start + n.count) as usize];
            tris.iter().any(|t| triangle_overlaps_box(t, c, h))
        };
        match near {
            Some(leaves) => {
                leaves.iter().map(|&i| &self.nodes[i as usize]).any(|n| n.bounds.overlaps(&grown) && leaf_touches(n))
            }
            None => self.leaves_meeting(&grown).any(|i| leaf_touches(&self.nodes[i as usize])),
        }
    }

    /// Appends to `out` the leaves (node indices) whose bounds meet `b` grown by 10⁻⁶ of
    /// its size (and by a few rounding units of its coordinates): every leaf that
    /// [`intersects_box`](Self::intersects_box) of a box inside `b` looks at. Looked for
    /// among `near` when given (the leaves near a box containing `b`). Gives up when
    /// more than `max` leaves are near: returns `false` and leaves `out` as it was.
    pub fn leaves_near(&self, b: &Aabb, near: Option<&[u32]>, out: &mut Vec<u32>, max: usize) -> bool {
        let e = b.extent();
        let pad = |k: usize| 1e-6 * e[k] + 16.0 * f64::EPSILON * b.lo[k].abs().max(b.hi[k].abs()) + f64::MIN_POSITIVE;
        let wide = Aabb { lo: [0, 1, 2].map(|k| b.lo[k] - pad(k)), hi: [0, 1, 2].map(|k| b.hi[k] + pad(k)) };
        let mut keep_at_most = |found: &mut dyn Iterator<Item = u32>| {
            let before = out.len();
            out.extend(found.take(max.saturating_add(1)));
            let within = out.len() - before <= max;
            if !within {
                out.truncate(before);
            }
            within
        };
        match near {
            Some(leaves) => {
                keep_at_most(&mut leaves.iter().copied().filter(|&i| self.nodes[i as usize].bounds.overlaps(&wide)))
            }
            None if self.nodes.is_empty() => true,
            None => keep_at_most(&mut self.leaves_meeting(&wide)),
        }
    }

    /// The leaves whose bounds meet `b`, found from the root (a query per octree cell:
    /// the walk's stack stays on the call stack).
    fn leaves_meeting<'a>(&'a self, b: &'a Aabb) -> impl Iterator<Item = u32> + 'a {
        let mut stack: SmallVec<[u32; 64]> = smallvec![0];
        std::iter::from_fn(move || {
            while let Some(i) = stack.pop() {
                let n = &self.nodes[i as usize];
                if !n.bounds.overlaps(b) {
                    continue;
                }
                if n.count > 0 {
                    return Some(i);
                }
                stack.extend([n.left, n.left + 1]);
            }
            None
        })
    }
}

/// The centre, half sizes and box of the contact test of `b`: grown by 10⁻¹⁰ of its
/// size, so that touching counts as intersecting.
fn touch_box(b: &Aabb) -> ([f64; 3], [f64; 3], Aabb) {
    let c = b.centre();
    let h = b.extent().map(|e| 0.5 * e * (1.0 + 1e-10) + f64::MIN_POSITIVE);
    (c, h, Aabb { lo: [0, 1, 2].map(|k| c[k] - h[k]), hi: [0, 1, 2].map(|k| c[k] + h[k]) })
}

fn tri_centroid(t: &[[f64; 3]; 3]) -> [f64; 3] {
    [0, 1, 2].map(|k| (t[0][k] + t[1][k] + t[2][k]) / 3.0)
}

/// Separating-axis test of a triangle against the box of centre `c` and half sizes `h`
/// (Akenine-Möller's 13 axes: 3 box normals, the triangle normal, 9 edge cross products).
pub fn triangle_overlaps_box(t: &[[f64; 3]; 3], c: [f64; 3], h: [f64; 3]) -> bool {
    let v = t.map(|p| sub(p, c));
    let units = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    if units.iter().any(|&u| separated(&v, h, u)) {
        return false;
    }
    let edges = [sub(v[1], v[0]), sub(v[2], v[1]), sub(v[0], v[2])];
    if separated(&v, h, cross(edges[0], edges[1])) {
        return false;
    }
    !edges.iter().any(|&e| units.iter().any(|&u| separated(&v, h, cross(e, u))))
}

/// Whether `axis` separates the triangle `v` (taken from the box's centre) from the box
/// of half-extents `h`. Always inlined: the surface's contact tests run it thirteen
/// times per triangle and box, and left to the compiler it was sometimes kept as a
/// call, its minimum and maximum as iterator folds (fertility L6, 1 thread: 8% of the
/// run's time between two builds that differed elsewhere).
#[inline(always)]
fn separated(v: &[[f64; 3]; 3], h: [f64; 3], axis: [f64; 3]) -> bool {
    let p = v.map(|x| super::dot(x, axis));
    let r = h[0] * axis[0].abs() + h[1] * axis[1].abs() + h[2] * axis[2].abs();
    p[0].min(p[1]).min(p[2]) > r || p[0].max(p[1]).max(p[2]) < -r
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_box() -> Aabb {
        Aabb { lo: [0.0; 3], hi: [1.0; 3] }
    }

    #[test]
    fn box_test_cases() {
        let b = unit_box();
        let hit = TriangleBvh::new(vec![[[0.5, 0.5, -1.0], [0.5, 0.5, 2.0], [3.0, 0.5, 0.5]]]);
        assert!(hit.intersects_box(&b));
        // Near the box's corner but beyond its diagonal plane: only the triangle-normal
        // or an edge axis separates it.
        let miss =
            TriangleBvh::new(vec![[[1.5, 0.0, 1.5], [1.5, 1.5, 0.0], [0.0, 1.5, 1.5]].map(|p| p.map(|c| c + 0.2))]);
        assert!(!miss.intersects_box(&b));
        let touching = TriangleBvh::new(vec![[[1.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 1.0, 0.0]]]);
        assert!(touching.intersects_box(&b));
    }

    #[test]
    fn bvh_agrees_with_brute_force() {
        // A fan of thin triangles around a helix, boxes on a grid.
        let tris: Vec<[[f64; 3]; 3]> = (0..200)
            .map(|i| {
                let a = i as f64 * 0.1;
                let p = [2.0 + a.cos(), 2.0 + a.sin(), a * 0.05];
                [p, [p[0] + 0.3, p[1], p[2]], [p[0], p[1] + 0.05, p[2] + 0.3]]
            })
            .collect();
        let bvh = TriangleBvh::new(tris.clone());
        for i in 0..8 {
            for j in 0..8 {
                for k in 0..4 {
                    let lo = [i as f64 * 0.5, j as f64 * 0.5, k as f64 * 0.5];
                    let b = Aabb { lo, hi: lo.map(|x| x + 0.5) };
                    let brute = tris.iter().any(|t| triangle_overlaps_box(t, b.centre(), b.extent().map(|e| e / 2.0)));
                    assert_eq!(bvh.intersects_box(&b), brute, "box {lo:?}");
                }
            }
        }
    }

    /// Octants and their octants tested among the leaves kept near their parent give
    /// the answers of the walk from the root, including for a triangle just outside
    /// the parent that only the children's grown test boxes reach.
    #[test]
    fn tests_near_a_parent_answer_as_from_the_root() {
        let mut tris: Vec<[[f64; 3]; 3]> = (0..300)
            .map(|i| {
                let a = i as f64 * 0.07;
                let p = [2.0 + 1.5 * a.cos(), 2.0 + 1.5 * a.sin(), 0.2 + a * 0.08];
                [p, [p[0] + 0.2, p[1], p[2]], [p[0], p[1] + 0.03, p[2] + 0.2]]
            })
            .collect();
        // In the plane x = 4 + 10⁻¹¹: outside the root box [0, 4]³, inside the grown
        // test boxes of the cells on its x = 4 side.
        let x = 4.0 + 1e-11;
        let beyond: Vec<[[f64; 3]; 3]> = (0..4)
            .map(|i| {
                let z = 3.6 + 0.05 * i as f64;
                [[x, 1.0, z], [x, 1.2, z], [x, 1.0, z + 0.04]]
            })
            .collect();
        tris.extend(&beyond);
        let bvh = TriangleBvh::new(tris);
        let octants = |b: &Aabb| -> Vec<Aabb> {
            let c = b.centre();
            (0..8)
                .map(|o| {
                    let high = |k: usize| o >> k & 1 == 1;
                    Aabb {
                        lo: [0, 1, 2].map(|k| if high(k) { c[k] } else { b.lo[k] }),
                        hi: [0, 1, 2].map(|k| if high(k) { b.hi[k] } else { c[k] }),
                    }
                })
                .collect()
        };
        let root = Aabb { lo: [0.0; 3], hi: [4.0; 3] };
        let (mut near_root, mut hits) = (Vec::new(), 0);
        assert!(bvh.leaves_near(&root, None, &mut near_root, usize::MAX));
        for child in octants(&root) {
            let mut near_child = Vec::new();
            assert!(bvh.leaves_near(&child, Some(&near_root), &mut near_child, usize::MAX));
            for grandchild in octants(&child) {
                let from_root = bvh.intersects_box(&grandchild);
                assert_eq!(bvh.intersects_box_near(&grandchild, Some(&near_child)), from_root, "{grandchild:?}");
                hits += usize::from(from_root);
            }
            assert_eq!(bvh.intersects_box_near(&child, Some(&near_root)), bvh.intersects_box(&child));
        }
        assert!(hits > 4, "the helix crosses several cells ({hits})");
        // Those triangles alone: the leaves meeting the root box itself miss them, the
        // leaves near it (with the pad) do not.
        let bvh = TriangleBvh::new(beyond);
        let side = Aabb { lo: [2.0, 0.0, 2.0], hi: [4.0, 2.0, 4.0] };
        assert!(bvh.intersects_box(&side));
        assert_eq!(bvh.leaves_meeting(&root).count(), 0);
        let mut near = Vec::new();
        assert!(!bvh.leaves_near(&root, None, &mut near, 0) && near.is_empty(), "more than none are near");
        assert!(bvh.leaves_near(&root, None, &mut near, usize::MAX));
        assert!(bvh.intersects_box_near(&side, Some(&near)));
    }
}
