//! The recombination rules stored compiled (`rules.bin`): per rule its word, its
//! automorphisms, its hexahedral corners and its target's diagonals, as
//! `compile_rule` (test-only) computes them from the catalogue. Reading them takes no query map:
//! a rule's map is rebuilt only when a match of it is replaced (its modify plan), so
//! a recombination starts in a fraction of a millisecond with a few hundred kilobytes
//! instead of compiling 330 query maps. A test checks the file against
//! `compile_rule` byte for byte and rewrites it with `QMESH_BLESS=1`.
//!
//! Layout (every number one byte unless said; labels fit in a byte, a rule has at most
//! 180 darts): the magic `QMHR`, the version, the rule count (2 bytes, little endian);
//! then per rule its oriented class (2 bytes), its number of darts n, its 8 corner
//! labels, its 6 × 2 diagonal labels, its `keep` label, its number of automorphisms a,
//! its word (3n symbols: a label, or 0 on a 3-free dart, whose condition is `↔`), and
//! a times: flags (bit 0: keeps the conditions, bit 1: a cube symmetry) then the n
//! labels of the image.

use super::HexSplits;
use super::rules::{HexRule, HexTarget, split_query_map};
use crate::cmap::{CMap3, Dart};
use crate::query::{Automorphisms, Condition, Query, QueryWord};

const MAGIC: &[u8; 4] = b"QMHR";
const VERSION: u8 = 1;
static STORED: &[u8] = include_bytes!("rules.bin");

/// The rules as stored (see the module's layout).
pub(super) fn stored_rules() -> Vec<HexRule> {
    decode(STORED)
}

/// The query map of oriented class `o` and the start dart of its rule's labelling:
/// how a stored rule's query gets its map when something needs it.
fn rule_query_map(o: u32) -> (CMap3, Dart) {
    let class = &HexSplits::get().oriented[o as usize];
    let points = class.realization.expect("only realised classes have rules");
    let start = class.query_start.and_then(Dart::from_raw).expect("realised classes have a start");
    (split_query_map(&class.tets, &points), start)
}

/// Bytes read in order from the stored table, which a test keeps complete.
struct Reader<'a>(&'a [u8]);

impl Reader<'_> {
    fn bytes(&mut self, n: usize) -> &[u8] {
        let (head, rest) = self.0.split_at(n);
        self.0 = rest;
        head
    }

    fn byte(&mut self) -> u8 {
        self.bytes(1)[0]
    }

    fn u16(&mut self) -> u16 {
        let b = self.bytes(2);
        u16::from_le_bytes([b[0], b[1]])
    }

    fn labels(&mut self, n: usize) -> Vec<u32> {
        self.bytes(n).iter().map(|&l| u32::from(l)).collect()
    }
}

fn decode(bytes: &[u8]) -> Vec<HexRule> {
    let mut r = Reader(bytes);
    assert!(r.bytes(4) == MAGIC && r.byte() == VERSION, "rules.bin is qmesh's rule table, version {VERSION}");
    let count = r.u16();
    let rules = (0..count)
        .map(|_| {
            let oriented = r.u16();
            let n = usize::from(r.byte());
            let corners: [u32; 8] = std::array::from_fn(|_| u32::from(r.byte()));
            let diagonals: [[u32; 2]; 6] = std::array::from_fn(|_| [r.byte(), r.byte()].map(u32::from));
            let keep = u32::from(r.byte());
            let nb_automorphisms = r.byte();
            let free = Condition::NoConnection.code();
            let word = r.bytes(3 * n).iter().map(|&s| if s == 0 { free } else { u32::from(s) }).collect();
            let images: Vec<(Vec<u32>, bool, bool)> = (0..nb_automorphisms)
                .map(|_| {
                    let flags = r.byte();
                    (r.labels(n), flags & 1 != 0, flags & 2 != 0)
                })
                .collect();
            let query = Query::stored(
                format!("hex-split-{oriented}"),
                QueryWord::from_symbols(word),
                Automorphisms::from_images(images),
                Some(corners),
                (rule_query_map, u32::from(oriented)),
            );
            HexRule { query, target: HexTarget { oriented: oriented.into(), corners, diagonals, keep } }
        })
        .collect();
    assert!(r.0.is_empty(), "rules.bin has nothing after its rules");
    rules
}

/// `rules` in the stored layout.
#[cfg(test)]
fn encode(rules: &[HexRule]) -> Vec<u8> {
    let label = |l: u32| u8::try_from(l).expect("labels fit in a byte");
    let mut out = MAGIC.to_vec();
    out.push(VERSION);
    out.extend(u16::try_from(rules.len()).expect("rule count").to_le_bytes());
    for rule in rules {
        let (q, t) = (&rule.query, &rule.target);
        out.extend(u16::try_from(t.oriented).expect("class index").to_le_bytes());
        out.push(label(q.nb_darts() as u32));
        assert_eq!(q.corners, Some(t.corners), "a rule's query reads its target's corners");
        out.extend(t.corners.map(label));
        out.extend(t.diagonals.iter().flatten().map(|&l| label(l)));
        out.push(label(t.keep));
        out.push(u8::try_from(q.automorphisms.images().count()).expect("automorphism count"));
        for (k, s) in q.word.symbols().enumerate() {
            let free = k % 3 == 2 && q.word.condition(k / 3 + 1).is_some();
            assert!(!free || q.word.condition(k / 3 + 1) == Some(Condition::NoConnection), "rules use ↔ only");
            out.push(if free { 0 } else { label(s) });
        }
        for (image, keeps, cube) in q.automorphisms.images() {
            out.push(u8::from(keeps) | u8::from(cube) << 1);
            out.extend(image.iter().map(|&l| label(l)));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::rules::compile_rule;
    use super::*;

    /// `rules.bin` is what compiling every realised class gives, byte for byte;
    /// `QMESH_BLESS=1` rewrites it.
    #[test]
    fn stored_rules_are_the_compiled_rules() {
        let splits = HexSplits::get();
        let compiled: Vec<HexRule> = (0..splits.oriented.len())
            .filter(|&o| splits.oriented[o].realization.is_some())
            .map(|o| compile_rule(splits, o).unwrap())
            .collect();
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/src/apps/hex_split/rules.bin");
        if std::env::var_os("QMESH_BLESS").is_some() {
            std::fs::write(path, encode(&compiled)).expect("rules.bin is writable");
        }
        let on_disk = std::fs::read(path).expect("rules.bin exists");
        assert!(on_disk == encode(&compiled), "rules.bin differs from the compiled rules: rerun with QMESH_BLESS=1");
        assert!(STORED == on_disk.as_slice(), "the binary embeds the current rules.bin: rebuild");
        let stored = stored_rules();
        assert_eq!(stored.len(), compiled.len());
        for (s, c) in stored.iter().zip(&compiled) {
            assert_eq!(s.query.name, c.query.name);
            assert_eq!(s.query.word, c.query.word);
            assert!(s.query.automorphisms.images().eq(c.query.automorphisms.images()), "{}", s.query.name);
            assert_eq!(s.query.corners, c.query.corners);
            assert_eq!(s.query.volume_labels(), c.query.volume_labels());
            assert_eq!(s.query.nb_volumes(), c.query.nb_volumes());
            assert_eq!((s.target.oriented, s.target.corners), (c.target.oriented, c.target.corners));
            assert_eq!((s.target.diagonals, s.target.keep), (c.target.diagonals, c.target.keep));
            // The map rebuilt on demand reads the stored word.
            let rebuilt = QueryWord::new(s.query.map(), s.query.labelling(), |_| Condition::NoConnection);
            assert_eq!(rebuilt, s.query.word, "{}", s.query.name);
        }
    }

    /// Both automorphism flags survive the layout, whatever their values (every rule
    /// of today's table keeps its conditions, all `↔`, so the table alone never shows
    /// a cleared first flag).
    #[test]
    fn automorphism_flags_round_trip() {
        let mut rules = stored_rules();
        let rule = rules.iter_mut().find(|r| r.query.automorphisms.images().count() >= 2).unwrap();
        let flipped: Vec<(Vec<u32>, bool, bool)> = rule
            .query
            .automorphisms
            .images()
            .enumerate()
            .map(|(k, (image, keeps, cube))| (image.to_vec(), keeps && k % 2 == 0, cube && k % 2 == 1))
            .collect();
        rule.query.automorphisms = Automorphisms::from_images(flipped.clone());
        let name = rule.query.name.clone();
        let back = decode(&encode(&rules));
        let again = back.iter().find(|r| r.query.name == name).unwrap();
        let read: Vec<(Vec<u32>, bool, bool)> =
            again.query.automorphisms.images().map(|(i, k, c)| (i.to_vec(), k, c)).collect();
        assert_eq!(read, flipped);
        assert!(flipped.iter().any(|f| !f.1) && flipped.iter().any(|f| f.2));
    }

    /// A table cut short or with another header is refused (by a panic: the table is
    /// compiled in, so this is a defect of qmesh, never of the user's input).
    #[test]
    fn a_damaged_table_is_refused() {
        for bad in [&STORED[..STORED.len() - 1], &STORED[1..]] {
            assert!(std::panic::catch_unwind(|| decode(bad)).is_err());
        }
    }
}
