//! Key script syntax: good input, and bad input reported with its line number.

use portalcast_harness::{KeyScript, KeyScriptError, Keys};

#[test]
fn single_frames_ranges_and_open_ranges() {
    let script: KeyScript = "10: A\n20-30: UP+L\n40-: START\n".parse().unwrap();
    assert_eq!(script.keys_at(9), Keys::NONE);
    assert_eq!(script.keys_at(10), Keys::A);
    assert_eq!(script.keys_at(11), Keys::NONE);
    assert_eq!(script.keys_at(20), Keys::UP | Keys::L);
    assert_eq!(script.keys_at(30), Keys::UP | Keys::L);
    assert_eq!(script.keys_at(31), Keys::NONE);
    assert_eq!(script.keys_at(40), Keys::START);
    assert_eq!(script.keys_at(1_000_000), Keys::START);
}

#[test]
fn comments_blank_lines_case_and_spacing_are_tolerated() {
    let text = "# walk forward, then fire\n\n  0 - 2 :  up + b  # both\n3: none\r\n4:select\n";
    let script = KeyScript::parse(text).unwrap();
    assert_eq!(script.keys_at(0), Keys::UP | Keys::B);
    assert_eq!(script.keys_at(2), Keys::UP | Keys::B);
    assert_eq!(script.keys_at(3), Keys::NONE);
    assert_eq!(script.keys_at(4), Keys::SELECT);
}

#[test]
fn overlapping_rules_add_up() {
    let script = KeyScript::parse("0-10: A\n5-: RIGHT\n").unwrap();
    assert_eq!(script.keys_at(4), Keys::A);
    assert_eq!(script.keys_at(5), Keys::A | Keys::RIGHT);
    assert_eq!(script.keys_at(11), Keys::RIGHT);
}

#[test]
fn code_and_text_agree_and_display_round_trips() {
    let built = KeyScript::new()
        .hold(10..=10, Keys::A)
        .hold(20..=30, Keys::UP | Keys::L)
        .hold_from(40, Keys::START);
    let parsed = KeyScript::parse("10: A\n20-30: UP+L\n40-: START").unwrap();
    assert_eq!(built, parsed);
    assert_eq!(built.to_string(), "10: A\n20-30: UP+L\n40-: START\n");
    assert_eq!(KeyScript::parse(&built.to_string()).unwrap(), built);
}

#[test]
fn empty_script_holds_nothing() {
    let script = KeyScript::parse("\n# nothing\n").unwrap();
    assert_eq!(script, KeyScript::new());
    assert_eq!(script.keys_at(0), Keys::NONE);
}

fn error_of(text: &str) -> KeyScriptError {
    KeyScript::parse(text).expect_err("the script must be rejected")
}

#[test]
fn unknown_key_is_reported_with_its_line() {
    let error = error_of("10: A\n\n20: JUMP\n");
    assert_eq!(error.line, 3);
    assert!(error.message.contains("JUMP"), "{error}");
    assert!(
        error.to_string().starts_with("key script line 3:"),
        "{error}"
    );
}

#[test]
fn missing_colon_is_reported_with_its_line() {
    let error = error_of("# header\n10 A\n");
    assert_eq!(error.line, 2);
    assert!(error.message.contains("FRAMES: KEYS"), "{error}");
}

#[test]
fn bad_frame_numbers_are_reported() {
    assert_eq!(error_of("ten: A").line, 1);
    assert_eq!(error_of("1: A\n-5: A").line, 2);
    assert_eq!(error_of("1: A\n2: B\n3-x: A").line, 3);
    assert_eq!(error_of("99999999999: A").line, 1);
}

#[test]
fn backwards_range_is_reported() {
    let error = error_of("30-20: UP");
    assert_eq!(error.line, 1);
    assert!(error.message.contains("ends before it starts"), "{error}");
}

#[test]
fn empty_key_lists_are_reported() {
    assert_eq!(error_of("1:").line, 1);
    assert_eq!(error_of("1: A\n2: A+").line, 2);
    assert_eq!(error_of("1: A++B").line, 1);
}

#[test]
fn keys_parse_and_display() {
    assert_eq!("up+l".parse::<Keys>().unwrap(), Keys::UP | Keys::L);
    assert_eq!((Keys::L | Keys::A).to_string(), "A+L");
    assert_eq!(Keys::NONE.to_string(), "NONE");
    assert_eq!(Keys::ALL.bits(), 0x3FF);
    assert_eq!(Keys::from_bits(0x400), None);
    assert_eq!(Keys::from_bits_truncate(0xFFFF), Keys::ALL);
    assert_eq!(Keys::A.keyinput(), 0x3FE);
    let mut keys = Keys::A | Keys::B;
    keys.remove(Keys::A);
    assert_eq!(keys, Keys::B);
    assert!(keys.contains(Keys::B) && !keys.contains(Keys::A));
}

#[test]
fn a_rom_recording_becomes_the_script_that_replays_it() {
    // Button changes at VBlanks 9 (UP), 20 (UP+L), 30 (nothing), 40 (A, to the end): the
    // sample of VBlank K holds the keys of frame K + 1.
    let log = [
        "player frame=0 x=1",
        "input vblank=9 keys=0x040",
        "input vblank=20 keys=0x240",
        "render map=bench frame=0",
        "input vblank=30 keys=0x000",
        "input vblank=40 keys=0x001",
    ];
    let script = KeyScript::from_rom_log(log);
    assert_eq!(script, "10-20: UP\n21-30: UP+L\n41-: A\n".parse().unwrap());
    for frame in 0..60 {
        let expected = match frame {
            10..=20 => Keys::UP,
            21..=30 => Keys::UP | Keys::L,
            41.. => Keys::A,
            _ => Keys::NONE,
        };
        assert_eq!(script.keys_at(frame), expected, "frame {frame}");
    }
}

#[test]
fn a_recording_with_keys_held_at_boot_holds_them_until_the_rom_saw_them_go() {
    // Start held at power-on (the ROM's per-frame lines), let go before the sample of VBlank 4:
    // the replay holds it on frames 0 to 4, then the game's own changes follow.
    let log = [
        "portalcast boot waitcnt=0x4317",
        "input boot keys=0x008 released_vblank=4",
        "play start vblank=6 map=bench",
        "input vblank=9 keys=0x040",
        "input vblank=20 keys=0x000",
    ];
    let script = KeyScript::from_rom_log(log);
    assert_eq!(script, "10-20: UP\n0-4: START\n".parse().unwrap());
    assert_eq!(script.keys_at(4), Keys::START);
    assert_eq!(script.keys_at(5), Keys::NONE);
}
