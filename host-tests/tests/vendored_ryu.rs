//! The firmware formats numbers with a patched `ryu` (`vendor/ryu`: no `ptr::copy` in the
//! `f32` layout, powers of 5 from small tables; its README). Here it must write the same
//! characters as crates.io's `ryu` 1.0.23 for every `f32` checked: a stride over all bit
//! patterns (both signs), every subnormal and normal boundary, powers of ten and their
//! neighbours, and seeded random patterns. (All 4,278,190,080 finite `f32` were compared
//! once, out of tree, when the patch was written.)

fn same(x: f32) {
    let mut upstream = ryu::Buffer::new();
    let mut vendored = ryu_vendored::Buffer::new();
    let (a, b) = (upstream.format_finite(x), vendored.format_finite(x));
    assert_eq!(a, b, "{x:e} (bits {:#010x})", x.to_bits());
}

#[test]
fn strided_bit_patterns_format_alike() {
    // 2^32 / 4,099 ≈ 1.05 million patterns; 4,099 is prime, so every exponent and low
    // mantissa bit is visited.
    let mut bits = 0u32;
    let mut checked = 0u32;
    loop {
        let x = f32::from_bits(bits);
        if x.is_finite() {
            same(x);
            checked += 1;
        }
        match bits.checked_add(4_099) {
            Some(next) => bits = next,
            None => break,
        }
    }
    assert!(checked > 1_000_000, "{checked}");
}

#[test]
fn boundaries_and_powers_of_ten_format_alike() {
    let mut values = vec![
        0.0,
        -0.0,
        f32::MIN_POSITIVE,
        f32::MAX,
        f32::MIN,
        f32::EPSILON,
        f32::from_bits(1),
        f32::from_bits(0x007f_ffff),
        12.34,
        0.1,
        1.0 / 3.0,
    ];
    for exponent in -45..=38 {
        let power = 10f32.powi(exponent);
        values.extend([power, power.next_up(), power.next_down()]);
    }
    for exponent in 0..=255u32 {
        let low = f32::from_bits(exponent << 23);
        values.extend([low, low.next_up(), low.next_down()]);
    }
    for x in values.into_iter().filter(|x| x.is_finite()) {
        same(x);
        same(-x);
    }
}

#[test]
fn random_bit_patterns_format_alike() {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    for _ in 0..1_000_000 {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        let x = f32::from_bits((state >> 32) as u32);
        if x.is_finite() {
            same(x);
        }
    }
}
