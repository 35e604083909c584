//! Annotation throughput of the 2025 query engine (symbols checked per second, about
//! three per dart visited): a 2×2×2 block of hexahedra matched from every dart of a
//! 20³ grid, on one thread and on all, and one word replayed from one dart.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use qmesh::build::{BuildOptions, build_volume_map};
use qmesh::cmap::Dart;
use qmesh::generate::hex_grid;
use qmesh::query::{Annotator, Condition, MatchOptions, Query, QuerySet, find_matches};

fn bench(c: &mut Criterion) {
    let opts = BuildOptions::default();
    let grid = build_volume_map(&hex_grid(20, 20, 20), &opts).unwrap().0;
    let block = build_volume_map(&hex_grid(2, 2, 2), &opts).unwrap().0;
    let set = QuerySet::new(vec![Query::new("block", block, |_| Condition::Any).unwrap()]);
    let steps = find_matches(&grid, &set, &MatchOptions::default()).steps;
    let mut g = c.benchmark_group("query");
    g.sample_size(10);
    g.throughput(Throughput::Elements(steps));
    g.bench_function("block2x2x2_grid20_all_threads", |b| {
        b.iter(|| find_matches(&grid, &set, &MatchOptions::default()))
    });
    let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    g.bench_function("block2x2x2_grid20_one_thread", |b| {
        b.iter(|| one.install(|| find_matches(&grid, &set, &MatchOptions::default())))
    });
    g.finish();
    let mut g = c.benchmark_group("annotate");
    g.throughput(Throughput::Elements(576));
    let q = &set.queries[0];
    let mut a = Annotator::new(q.nb_darts());
    let start = Dart::from_raw(1).unwrap();
    g.bench_function("one_match_576_symbols", |b| b.iter(|| a.annotate(&grid, &q.word, start, None)));
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
