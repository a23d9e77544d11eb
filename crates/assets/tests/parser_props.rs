//! The parsers and checks never panic: any input yields a compiled map or errors. And any grid
//! drawn from valid cell kinds compiles, which exercises the rectangle merging and T-junction
//! splitting on shapes nobody wrote by hand.

mod common;

use common::shipped_assets;
use portalcast_assets::{compile_map_str, Catalog};
use proptest::prelude::*;

fn catalog() -> Catalog {
    Catalog::new(
        [
            "brick", "ceiling", "dirt", "grass", "marble", "metal", "step", "stone", "tiles",
            "trim", "water", "wood",
        ],
        ["torch"],
        true,
    )
}

fn shipped(name: &str) -> String {
    std::fs::read_to_string(shipped_assets().join("maps").join(name)).expect("shipped map")
}

/// Compiles and checks only that the result is well formed: errors are one located line each.
fn compile_without_panic(file_name: &str, text: &str) {
    if let Err(errors) = compile_map_str(file_name, text, &catalog()) {
        assert!(!errors.0.is_empty());
        for error in &errors.0 {
            assert!(error.loc.line >= 1 && error.loc.col >= 1);
            assert!(!error.message.contains('\n'));
        }
    }
}

/// Words that mean something to the parsers, plus troublemakers.
const VOCABULARY: &[&str] = &[
    "vertex",
    "sector",
    "wall",
    "player",
    "thing",
    "grid",
    "cell",
    "solid",
    "open",
    "portal=a",
    "floor=",
    "ceil=64",
    "tex=brick",
    "upper=stone",
    "lower=step",
    "xoff=-3",
    "angle=90.5",
    "floor_tex=sky",
    "ceil_tex=sky",
    "light=999",
    "on=.",
    "side=step",
    "=",
    "==",
    "#",
    ".",
    "@",
    "0",
    "-1",
    "32.5",
    "99999999999999999999",
    "-0.00000000000001",
    "9223372036854775807",
    "8192",
    "-8192",
    "v0",
    "v1",
    "hall",
    "torch",
    "é",
    "\t",
    "x=y=z",
];

#[derive(Clone, Debug)]
enum Mutation {
    DeleteLine(usize),
    DuplicateLine(usize),
    SwapLines(usize, usize),
    ReplaceWord(usize, usize, usize),
    InsertChar(usize, char),
    Truncate(usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        any::<usize>().prop_map(Mutation::DeleteLine),
        any::<usize>().prop_map(Mutation::DuplicateLine),
        (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Mutation::SwapLines(a, b)),
        (any::<usize>(), any::<usize>(), 0..VOCABULARY.len())
            .prop_map(|(l, w, v)| Mutation::ReplaceWord(l, w, v)),
        (any::<usize>(), any::<char>()).prop_map(|(at, c)| Mutation::InsertChar(at, c)),
        any::<usize>().prop_map(Mutation::Truncate),
    ]
}

fn mutate(text: &str, mutations: &[Mutation]) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    for m in mutations {
        if lines.is_empty() {
            break;
        }
        let n = lines.len();
        match *m {
            Mutation::DeleteLine(i) => {
                lines.remove(i % n);
            }
            Mutation::DuplicateLine(i) => {
                let line = lines[i % n].clone();
                lines.insert(i % n, line);
            }
            Mutation::SwapLines(a, b) => lines.swap(a % n, b % n),
            Mutation::ReplaceWord(l, w, v) => {
                let mut words: Vec<String> = lines[l % n].split(' ').map(str::to_string).collect();
                let count = words.len();
                words[w % count] = VOCABULARY[v].to_string();
                lines[l % n] = words.join(" ");
            }
            Mutation::InsertChar(at, c) => {
                let line = &mut lines[at % n];
                let chars: Vec<char> = line.chars().collect();
                let position = at % (chars.len() + 1);
                *line = chars[..position]
                    .iter()
                    .chain([c].iter())
                    .chain(chars[position..].iter())
                    .collect();
            }
            Mutation::Truncate(at) => lines.truncate(at % n),
        }
    }
    lines.join("\n")
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn arbitrary_text_never_panics(text in any::<String>(), grid in any::<bool>()) {
        compile_without_panic(if grid { "x.grid" } else { "x.map" }, &text);
    }

    #[test]
    fn word_soup_never_panics(words in prop::collection::vec((0..VOCABULARY.len(), 0..8u8), 0..80), grid in any::<bool>()) {
        let mut text = String::new();
        for (word, separator) in words {
            text.push_str(VOCABULARY[word]);
            text.push(if separator == 0 { '\n' } else { ' ' });
        }
        compile_without_panic(if grid { "x.grid" } else { "x.map" }, &text);
    }

    #[test]
    fn mutated_text_maps_never_panic(mutations in prop::collection::vec(mutation(), 1..6), which in 0..2usize) {
        let name = ["tiny.map", "bench.map"][which];
        compile_without_panic(name, &mutate(&shipped(name), &mutations));
    }

    #[test]
    fn mutated_grid_maps_never_panic(mutations in prop::collection::vec(mutation(), 1..6)) {
        compile_without_panic("grid.grid", &mutate(&shipped("grid.grid"), &mutations));
    }

    #[test]
    fn any_grid_of_valid_kinds_compiles(
        cells in prop::collection::vec(prop::collection::vec(0..7u8, 1..12), 1..12),
        player_at in any::<usize>(),
    ) {
        let width = cells.iter().map(Vec::len).max().unwrap_or(1);
        let symbols = ['#', 'S', '.', ',', '-', '=', '~'];
        let mut rows: Vec<String> = cells
            .iter()
            .map(|row| (0..width).map(|c| symbols[usize::from(*row.get(c).unwrap_or(&0))]).collect())
            .collect();
        // Put the player on some cell (it stands on '.').
        let (r, c) = ((player_at / width) % rows.len(), player_at % width);
        let mut chars: Vec<char> = rows[r].chars().collect();
        chars[c] = '@';
        rows[r] = chars.into_iter().collect();
        let border = "#".repeat(width + 2);
        let mut text = String::from(
            "cell 32\nsolid # tex=brick\nsolid S tex=stone\n\
             open . floor=0 ceil=128 floor_tex=tiles ceil_tex=ceiling side=brick\n\
             open , floor=0 ceil=256 floor_tex=grass ceil_tex=sky side=stone\n\
             open - floor=16 ceil=128 floor_tex=wood ceil_tex=ceiling side=step\n\
             open = floor=32 ceil=200 floor_tex=wood ceil_tex=sky side=step\n\
             open ~ floor=-16 ceil=96 floor_tex=water ceil_tex=ceiling side=stone\n\
             player @ on=.\ngrid\n",
        );
        text.push_str(&border);
        text.push('\n');
        for row in &rows {
            text.push_str(&format!("#{row}#\n"));
        }
        text.push_str(&border);
        let result = compile_map_str("random.grid", &text, &catalog());
        prop_assert!(result.is_ok(), "{}\n{}", text, result.err().map(|e| e.to_string()).unwrap_or_default());
        let map = result.unwrap_or_else(|_| unreachable!());
        let open_cells = text.lines().skip(10).flat_map(|l| l.chars()).filter(|c| !matches!(c, '#' | 'S')).count();
        prop_assert!(map.sectors.len() <= open_cells);
    }
}

#[test]
fn too_many_vertices_is_an_error_not_a_panic() {
    let mut text = String::new();
    for i in 0..65_536 {
        text.push_str(&format!("vertex v{i} {} {}\n", i % 256, i / 256));
    }
    text.push_str("player 0.5 0.5\n");
    let errors = compile_map_str("big.map", &text, &catalog()).expect_err("too many vertices");
    assert!(
        errors
            .to_string()
            .contains("more than the tables can index"),
        "{errors}"
    );
}
