//! Random and mutated inputs: the reader must return (Ok or Err), never panic or hang. This is
//! the always-on companion of the cargo-fuzz target in `fuzz/`, and holds the inputs the fuzzer
//! found.

use std::time::{Duration, Instant};

use platener::read::stl::parse_bytes;
use platener::read::{Format, ReadErrorKind};
use platener_geom::rng::SplitMix64;

/// The project's seeded generator, with a helper for indices.
struct Rng(SplitMix64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0.next_u64()
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

const SEEDS: &[&[u8]] = &[
    b"solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid a\n",
    b"SOLID\r\n FACET\r\n VERTEX 1e-3 -2.5E+2 .5\r\n vertex 1 2 3\r\n vertex nan 0 0\r\nENDFACET\r\n",
    b"solid x\n\0\0\0\0",
];

/// Mutations of valid files: byte flips, cut-offs, duplicated and inserted ranges.
fn mutate(rng: &mut Rng, input: &[u8]) -> Vec<u8> {
    let mut bytes = input.to_vec();
    for _ in 0..=rng.below(4) {
        let at = rng.below(bytes.len() + 1);
        match rng.below(5) {
            0 if at < bytes.len() => bytes[at] = rng.next() as u8,
            1 => bytes.truncate(at),
            2 => {
                let end = (at + rng.below(64)).min(bytes.len());
                let copy = bytes[at..end].to_vec();
                bytes.splice(at..at, copy);
            }
            3 => {
                let token: &[u8] =
                    [&b"facet "[..], b"vertex ", b"\n", b"endsolid", b"1e99999", b"\r", b"\0"][rng.below(7)];
                bytes.splice(at..at, token.iter().copied());
            }
            _ if bytes.len() >= 84 => {
                let count = (rng.next() as u32) >> rng.below(32);
                bytes[80..84].copy_from_slice(&count.to_le_bytes());
            }
            _ => {}
        }
    }
    bytes
}

fn binary_seed(rng: &mut Rng, facets: usize, header: &[u8]) -> Vec<u8> {
    let mut bytes = header.to_vec();
    bytes.resize(80, 0);
    bytes.extend_from_slice(&(facets as u32).to_le_bytes());
    for _ in 0..facets * 50 {
        bytes.push(rng.next() as u8);
    }
    bytes
}

#[test]
fn random_and_mutated_inputs_never_panic() {
    let start = Instant::now();
    let mut rng = Rng(SplitMix64::new(0xDEAD_BEEF_CAFE_F00D));
    let mut seeds: Vec<Vec<u8>> = SEEDS.iter().map(|s| s.to_vec()).collect();
    seeds.push(binary_seed(&mut rng, 20, b"solid binary"));
    seeds.push(binary_seed(&mut rng, 3, b"plain header"));
    for round in 0..20_000 {
        let input = if round % 4 == 0 {
            (0..rng.below(300)).map(|_| rng.next() as u8).collect()
        } else {
            let seed = &seeds[rng.below(seeds.len())];
            mutate(&mut rng, seed)
        };
        let _ = parse_bytes(&input);
    }
    assert!(start.elapsed() < Duration::from_secs(60), "took {:?}", start.elapsed());
}

/// Edge inputs written while fuzzing (the cargo-fuzz runs found no crash so far); add every
/// future fuzz finding here with the outcome it must have.
#[test]
fn fuzz_edge_inputs_have_the_right_outcome() {
    let syntax_line = |input: &[u8]| match parse_bytes(input) {
        Err(ReadErrorKind::Syntax { line, .. }) => line,
        other => panic!("{:?}: {other:?}", String::from_utf8_lossy(input)),
    };
    assert!(matches!(parse_bytes(b"solid"), Ok((Format::StlAscii, m)) if m.triangles.is_empty()));
    assert_eq!(syntax_line(b"\xEF\xBB\xBFsolid\nfacet\n"), 2);
    assert_eq!(syntax_line(b"solid\nfacet normal 1 2\n"), 2);
    let five = b"solid\nfacet\nvertex 0 0 0\nvertex 0 0 0\nvertex 0 0 0\nvertex 0 0 0\nvertex 0 0 0\nendfacet\n";
    assert_eq!(syntax_line(five), 8);
    // Binary bytes in a short file that starts like ASCII: not ASCII, too short for binary.
    let binary_tail = parse_bytes(b"solid\nendsolid\nsolid\n\x01\n");
    assert_eq!(binary_tail.err(), Some(ReadErrorKind::TooShort { actual: 23 }));
    // A count field of u32::MAX must not make the reader reserve 200 GB.
    let mut huge = vec![b' '; 80];
    huge.extend_from_slice(&u32::MAX.to_le_bytes());
    huge.extend_from_slice(&[0; 100]);
    assert!(matches!(parse_bytes(&huge), Err(ReadErrorKind::CountMismatch { .. })));
}
