//! Criterion benchmarks of the map core: building from indexed cells, orbit
//! traversals (cell counts, validity) and edge splitting.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use qmesh::build::{BuildOptions, build_volume_map, count_cell_kinds};
use qmesh::cmap::Orbit;
use qmesh::generate::{hex_grid, tet_grid};

fn build(c: &mut Criterion) {
    let mut g = c.benchmark_group("build");
    for n in [10usize, 30] {
        let hexes = hex_grid(n, n, n);
        g.bench_with_input(BenchmarkId::new("hex_grid", n), &hexes, |b, m| {
            b.iter(|| build_volume_map(m, &BuildOptions::default()).unwrap())
        });
    }
    let tets = tet_grid(15, 15, 15);
    g.bench_function("tet_grid/15", |b| b.iter(|| build_volume_map(&tets, &BuildOptions::default()).unwrap()));
    g.finish();
}

fn traverse(c: &mut Criterion) {
    let (map, _) = build_volume_map(&hex_grid(30, 30, 30), &BuildOptions::default()).unwrap();
    let mut g = c.benchmark_group("traverse_hex30");
    for o in [Orbit::Vertex, Orbit::Edge, Orbit::Face, Orbit::Volume] {
        g.bench_function(format!("{o:?}"), |b| b.iter(|| map.cells(o).count()));
    }
    g.bench_function("count_cells", |b| b.iter(|| map.count_cells()));
    g.bench_function("census", |b| b.iter(|| map.census()));
    g.bench_function("is_valid", |b| b.iter(|| map.is_valid()));
    g.bench_function("cell_kinds", |b| b.iter(|| count_cell_kinds(&map)));
    g.finish();
}

fn split(c: &mut Criterion) {
    let (map, _) = build_volume_map(&hex_grid(15, 15, 15), &BuildOptions::default()).unwrap();
    c.bench_function("split_all_edges_in_2/hex15", |b| {
        b.iter_batched(|| map.clone(), |mut m| m.split_all_edges(2).unwrap(), criterion::BatchSize::LargeInput)
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = build, traverse, split
}
criterion_main!(benches);
