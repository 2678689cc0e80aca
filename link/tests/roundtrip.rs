//! Property test: arbitrary values of every request and answer type, with every nested
//! type (the typed errors with each variant, `cuesight::Error` and `Field`, heapless
//! vectors and strings up to their capacities, `f32` of every bit pattern: NaN with any
//! payload, ±∞, −0, subnormals), through the whole link:
//!
//! host encode ([`frame::encode`]) → device decode ([`FrameReader`] byte by byte,
//! [`frame::open`], [`frame::decode`]) → device encode → host decode (a reference
//! decoder written here from the frame layout: its own COBS and CRC-32), and the value
//! at the end is the value at the start, compared field by field and bit for bit (a
//! serde walk that records every `f32` as its bits, so `NaN` equals itself and `−0`
//! does not equal `0`).
//!
//! Every encoded frame is at most [`MAX_FRAME`] bytes (its raw content at most
//! [`MAX_RAW`]), has exactly one `0x00`, at its end, and the device's re-encoding is
//! byte for byte the host's. A strategy cannot skip a variant silently:
//! `strategies_reach_every_variant` draws values and requires every variant of every
//! enum of the schema, the variant lists read from the types' own `Deserialize` (so a
//! variant added to the schema fails it until a strategy draws it).

use std::collections::BTreeSet;
use std::fmt::Debug;

use cuesight::validity::{Reason, Tier};
use cuesight::{Error as CoreError, Field};
use cuesight_link::error::{FrameFault, NoAim, SequenceFault, Unsupported};
use cuesight_link::frame::{self, FrameReader, Received, MAX_FRAME, MAX_RAW};
use cuesight_link::live::{
    FollowThrough, LiveReport, LiveStroke, SensorFault, StrokeMetrics, TraceEnd,
};
use cuesight_link::names::{EndName, ModelName, RegimeName, ShotMode, TableName};
use cuesight_link::response::{
    BallAnswer, ImpulsesAnswer, InputEcho, ParamsAnswer, ShutdownAnswer, StrokeProgress, NAME_LEN,
};
use cuesight_link::shot::{BallPart, ContactPart, SolvePart, StrokePart, TargetPart};
use cuesight_link::{
    Collide, CollideAnswer, Empty, LinkError, Overrides, Request, Response, ShotAnswer,
    ShotRequest, StrokeAnswer, StrokeChunk, StrokeSetup, UploadFault, VersionAnswer,
    MAX_OBJECT_BALLS, MAX_SAMPLES, SCHEMA_HASH,
};
use cuesight_sensors::{ConfigField, GlitchKind, StreamFault, StrokeError};
use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};
use serde::de::DeserializeOwned;
use serde::Serialize;

// ---------------------------------------------------------------------------------------
// Values compared bit for bit: a serde walk into tokens.

mod tokens {
    //! A serde serializer that writes a value as a list of tokens: every field name,
    //! variant and length, integers by value, floats by their bits.

    use serde::ser::{self, Serialize};
    use std::fmt;

    #[derive(Clone, Debug, PartialEq, Eq)]
    pub enum Tok {
        Bool(bool),
        Int(i128),
        F32(u32),
        F64(u64),
        Char(char),
        Str(String),
        Bytes(Vec<u8>),
        None,
        Some,
        Unit,
        UnitStruct(&'static str),
        NewtypeStruct(&'static str),
        Variant {
            ty: &'static str,
            index: u32,
            name: &'static str,
        },
        Seq(Option<usize>),
        Tuple(usize),
        TupleStruct(&'static str, usize),
        Map(Option<usize>),
        Struct(&'static str, usize),
        Field(&'static str),
        End,
    }

    #[derive(Debug)]
    pub struct Failed(String);

    impl fmt::Display for Failed {
        fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            f.write_str(&self.0)
        }
    }

    impl std::error::Error for Failed {}

    impl ser::Error for Failed {
        fn custom<T: fmt::Display>(msg: T) -> Self {
            Failed(msg.to_string())
        }
    }

    /// The tokens of `value`.
    pub fn of<T: Serialize + ?Sized>(value: &T) -> Vec<Tok> {
        let mut tokens = Tokens(Vec::new());
        value
            .serialize(&mut tokens)
            .expect("every schema type serializes");
        tokens.0
    }

    pub struct Tokens(Vec<Tok>);

    type R = Result<(), Failed>;

    impl Tokens {
        fn push(&mut self, tok: Tok) -> R {
            self.0.push(tok);
            Ok(())
        }
    }

    impl ser::Serializer for &mut Tokens {
        type Ok = ();
        type Error = Failed;
        type SerializeSeq = Self;
        type SerializeTuple = Self;
        type SerializeTupleStruct = Self;
        type SerializeTupleVariant = Self;
        type SerializeMap = Self;
        type SerializeStruct = Self;
        type SerializeStructVariant = Self;

        fn serialize_bool(self, v: bool) -> R {
            self.push(Tok::Bool(v))
        }
        fn serialize_i8(self, v: i8) -> R {
            self.push(Tok::Int(v.into()))
        }
        fn serialize_i16(self, v: i16) -> R {
            self.push(Tok::Int(v.into()))
        }
        fn serialize_i32(self, v: i32) -> R {
            self.push(Tok::Int(v.into()))
        }
        fn serialize_i64(self, v: i64) -> R {
            self.push(Tok::Int(v.into()))
        }
        fn serialize_i128(self, v: i128) -> R {
            self.push(Tok::Int(v))
        }
        fn serialize_u8(self, v: u8) -> R {
            self.push(Tok::Int(v.into()))
        }
        fn serialize_u16(self, v: u16) -> R {
            self.push(Tok::Int(v.into()))
        }
        fn serialize_u32(self, v: u32) -> R {
            self.push(Tok::Int(v.into()))
        }
        fn serialize_u64(self, v: u64) -> R {
            self.push(Tok::Int(v.into()))
        }
        fn serialize_f32(self, v: f32) -> R {
            self.push(Tok::F32(v.to_bits()))
        }
        fn serialize_f64(self, v: f64) -> R {
            self.push(Tok::F64(v.to_bits()))
        }
        fn serialize_char(self, v: char) -> R {
            self.push(Tok::Char(v))
        }
        fn serialize_str(self, v: &str) -> R {
            self.push(Tok::Str(v.to_owned()))
        }
        fn serialize_bytes(self, v: &[u8]) -> R {
            self.push(Tok::Bytes(v.to_vec()))
        }
        fn serialize_none(self) -> R {
            self.push(Tok::None)
        }
        fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> R {
            self.push(Tok::Some)?;
            value.serialize(self)
        }
        fn serialize_unit(self) -> R {
            self.push(Tok::Unit)
        }
        fn serialize_unit_struct(self, name: &'static str) -> R {
            self.push(Tok::UnitStruct(name))
        }
        fn serialize_unit_variant(self, ty: &'static str, index: u32, name: &'static str) -> R {
            self.push(Tok::Variant { ty, index, name })
        }
        fn serialize_newtype_struct<T: Serialize + ?Sized>(
            self,
            name: &'static str,
            value: &T,
        ) -> R {
            self.push(Tok::NewtypeStruct(name))?;
            value.serialize(self)
        }
        fn serialize_newtype_variant<T: Serialize + ?Sized>(
            self,
            ty: &'static str,
            index: u32,
            name: &'static str,
            value: &T,
        ) -> R {
            self.push(Tok::Variant { ty, index, name })?;
            value.serialize(self)
        }
        fn serialize_seq(self, len: Option<usize>) -> Result<Self, Failed> {
            self.push(Tok::Seq(len))?;
            Ok(self)
        }
        fn serialize_tuple(self, len: usize) -> Result<Self, Failed> {
            self.push(Tok::Tuple(len))?;
            Ok(self)
        }
        fn serialize_tuple_struct(self, name: &'static str, len: usize) -> Result<Self, Failed> {
            self.push(Tok::TupleStruct(name, len))?;
            Ok(self)
        }
        fn serialize_tuple_variant(
            self,
            ty: &'static str,
            index: u32,
            name: &'static str,
            len: usize,
        ) -> Result<Self, Failed> {
            self.push(Tok::Variant { ty, index, name })?;
            self.push(Tok::Tuple(len))?;
            Ok(self)
        }
        fn serialize_map(self, len: Option<usize>) -> Result<Self, Failed> {
            self.push(Tok::Map(len))?;
            Ok(self)
        }
        fn serialize_struct(self, name: &'static str, len: usize) -> Result<Self, Failed> {
            self.push(Tok::Struct(name, len))?;
            Ok(self)
        }
        fn serialize_struct_variant(
            self,
            ty: &'static str,
            index: u32,
            name: &'static str,
            len: usize,
        ) -> Result<Self, Failed> {
            self.push(Tok::Variant { ty, index, name })?;
            self.push(Tok::Struct(name, len))?;
            Ok(self)
        }
    }

    macro_rules! compound {
        ($($trait:ident :: $method:ident),*) => {$(
            impl ser::$trait for &mut Tokens {
                type Ok = ();
                type Error = Failed;
                fn $method<T: Serialize + ?Sized>(&mut self, value: &T) -> R {
                    value.serialize(&mut **self)
                }
                fn end(self) -> R {
                    self.push(Tok::End)
                }
            }
        )*};
    }
    compound!(
        SerializeSeq::serialize_element,
        SerializeTuple::serialize_element,
        SerializeTupleStruct::serialize_field,
        SerializeTupleVariant::serialize_field
    );

    impl ser::SerializeMap for &mut Tokens {
        type Ok = ();
        type Error = Failed;
        fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> R {
            key.serialize(&mut **self)
        }
        fn serialize_value<T: Serialize + ?Sized>(&mut self, value: &T) -> R {
            value.serialize(&mut **self)
        }
        fn end(self) -> R {
            self.push(Tok::End)
        }
    }

    macro_rules! fields {
        ($($trait:ident),*) => {$(
            impl ser::$trait for &mut Tokens {
                type Ok = ();
                type Error = Failed;
                fn serialize_field<T: Serialize + ?Sized>(
                    &mut self,
                    key: &'static str,
                    value: &T,
                ) -> R {
                    self.push(Tok::Field(key))?;
                    value.serialize(&mut **self)
                }
                fn end(self) -> R {
                    self.push(Tok::End)
                }
            }
        )*};
    }
    fields!(SerializeStruct, SerializeStructVariant);
}

mod probe {
    //! An enum's name and variant names, read from its `Deserialize` (which hands them
    //! to `deserialize_enum`).

    use serde::de::{self, Deserialize, Deserializer, Visitor};
    use std::fmt;

    #[derive(Debug)]
    pub struct Found(Option<(&'static str, &'static [&'static str])>);

    impl fmt::Display for Found {
        fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            write!(f, "{:?}", self.0)
        }
    }

    impl std::error::Error for Found {}

    impl de::Error for Found {
        fn custom<T: fmt::Display>(_: T) -> Self {
            Found(None)
        }
    }

    struct Probe;

    impl<'de> Deserializer<'de> for Probe {
        type Error = Found;

        fn deserialize_any<V: Visitor<'de>>(self, _: V) -> Result<V::Value, Found> {
            Err(Found(None))
        }

        fn deserialize_enum<V: Visitor<'de>>(
            self,
            name: &'static str,
            variants: &'static [&'static str],
            _: V,
        ) -> Result<V::Value, Found> {
            Err(Found(Some((name, variants))))
        }

        serde::forward_to_deserialize_any! {
            bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes
            byte_buf option unit unit_struct newtype_struct seq tuple tuple_struct map
            struct identifier ignored_any
        }
    }

    /// `T`'s serde name and variants (as written: renamed).
    pub fn variants<'de, T: Deserialize<'de>>() -> (&'static str, &'static [&'static str]) {
        match T::deserialize(Probe) {
            Err(Found(Some(found))) => found,
            _ => panic!("{} is not an enum", std::any::type_name::<T>()),
        }
    }
}

/// Every value of a fieldless enum, from its variant names.
fn all_units<T: DeserializeOwned>() -> Vec<T> {
    let (_, names) = probe::variants::<T>();
    names
        .iter()
        .map(|name| {
            serde_json::from_value(serde_json::Value::String((*name).into()))
                .unwrap_or_else(|e| panic!("{name}: not a fieldless variant ({e})"))
        })
        .collect()
}

// ---------------------------------------------------------------------------------------
// The reference decoder: the frame layout of link/src/frame.rs, written out again.

/// COBS-decodes one frame (without its zero), or `None` if it is not valid COBS.
fn cobs_decode(encoded: &[u8]) -> Option<Vec<u8>> {
    let mut raw = Vec::new();
    let mut i = 0;
    while i < encoded.len() {
        let code = usize::from(encoded[i]);
        if code == 0 || i + code > encoded.len() {
            return None;
        }
        raw.extend_from_slice(&encoded[i + 1..i + code]);
        i += code;
        if code < 0xff && i < encoded.len() {
            raw.push(0);
        }
    }
    Some(raw)
}

/// CRC-32/ISO-HDLC (reflected 0x04C11DB7, init and xor-out all ones), bit by bit.
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = u32::MAX;
    for &b in bytes {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// The host's decoding of one whole frame (zero included): schema, seq and the message.
fn reference_decode<T: DeserializeOwned>(wire: &[u8]) -> (u32, u16, T) {
    let (&zero, encoded) = wire.split_last().expect("a frame");
    assert_eq!(zero, 0, "a frame ends in 0x00");
    let raw = cobs_decode(encoded).expect("valid COBS");
    assert!(raw.len() >= 10, "raw frame of {} bytes", raw.len());
    let (content, crc) = raw.split_at(raw.len() - 4);
    assert_eq!(
        u32::from_le_bytes(crc.try_into().unwrap()),
        crc32(content),
        "CRC"
    );
    let schema = u32::from_le_bytes(content[..4].try_into().unwrap());
    let seq = u16::from_le_bytes(content[4..6].try_into().unwrap());
    let (message, rest) = postcard::take_from_bytes::<T>(&content[6..]).expect("a message");
    assert!(rest.is_empty(), "{} bytes after the message", rest.len());
    (schema, seq, message)
}

/// What every encoded frame is: short enough, one zero, at its end.
fn check_wire(wire: &[u8]) {
    assert!(
        wire.len() <= MAX_FRAME,
        "frame of {} bytes > MAX_FRAME",
        wire.len()
    );
    assert_eq!(wire.last(), Some(&0), "a frame ends in 0x00");
    assert_eq!(
        wire.iter().filter(|&&b| b == 0).count(),
        1,
        "exactly one 0x00 in {wire:?}"
    );
}

/// The device's decoding: the bytes one by one through a [`FrameReader`] (the frame
/// comes out at the last byte and no earlier), then `open` and `decode`.
fn device_decode<T: DeserializeOwned>(wire: &[u8], seq: u16) -> T {
    let mut reader = FrameReader::new();
    let (last, rest) = wire.split_last().expect("a frame");
    for &byte in rest {
        assert!(reader.push(byte).is_none(), "a frame before its zero");
    }
    let raw = match reader.push(*last) {
        Some(Received::Frame(raw)) => raw.to_vec(),
        other => panic!("frame reader: {other:?}"),
    };
    assert!(raw.len() <= MAX_RAW, "raw frame of {} bytes", raw.len());
    let (header, body) = frame::open(&raw).expect("the frame opens");
    assert_eq!((header.schema, header.seq), (SCHEMA_HASH, seq), "header");
    frame::decode::<T>(body).expect("the body decodes")
}

/// The round trip of the module docs; returns the final value's tokens.
fn round_trip<T>(value: &T, seq: u16)
where
    T: Serialize + DeserializeOwned + Debug,
{
    let mut wire = [0u8; MAX_FRAME];
    let len = frame::encode(SCHEMA_HASH, seq, value, &mut wire)
        .unwrap_or_else(|e| panic!("host encode: {e:?} for {value:?}"));
    let wire = &wire[..len];
    check_wire(wire);
    let on_device: T = device_decode(wire, seq);
    let mut answer = [0u8; MAX_FRAME];
    let len = frame::encode(SCHEMA_HASH, seq, &on_device, &mut answer)
        .unwrap_or_else(|e| panic!("device encode: {e:?} for {on_device:?}"));
    let answer = &answer[..len];
    check_wire(answer);
    assert_eq!(
        answer, wire,
        "the device's encoding differs from the host's"
    );
    let (schema, answer_seq, on_host) = reference_decode::<T>(answer);
    assert_eq!((schema, answer_seq), (SCHEMA_HASH, seq), "header");
    assert_eq!(
        tokens::of(&on_host),
        tokens::of(value),
        "{on_host:?} came back for {value:?}"
    );
}

// ---------------------------------------------------------------------------------------
// Strategies.

/// `f32` bit patterns worth having often: NaNs (quiet, signalling, negative, with a
/// payload), ±∞, ±0, the smallest and largest subnormals, the extremes.
const SPECIAL_F32: [u32; 17] = [
    0x7fc0_0000, // NaN
    0xffc0_0000, // −NaN
    0x7f80_0001, // signalling NaN
    0x7fc1_2345, // NaN with a payload
    0xffff_ffff, // NaN, every bit
    0x7f80_0000, // +∞
    0xff80_0000, // −∞
    0x0000_0000, // +0
    0x8000_0000, // −0
    0x0000_0001, // smallest subnormal
    0x8000_0001,
    0x007f_ffff, // largest subnormal
    0x0080_0000, // smallest normal
    0x7f7f_ffff, // MAX
    0xff7f_ffff, // MIN
    0x3f80_0000, // 1
    0x3400_0000, // EPSILON
];

fn f32s() -> BoxedStrategy<f32> {
    prop_oneof![
        3 => -1.0e3f32..1.0e3,
        3 => any::<u32>().prop_map(f32::from_bits),
        2 => prop::sample::select(SPECIAL_F32.to_vec()).prop_map(f32::from_bits),
    ]
    .boxed()
}

fn opt_f32s() -> impl Strategy<Value = Option<f32>> {
    prop::option::of(f32s())
}

/// `n` floats.
fn floats(n: usize) -> impl Strategy<Value = Vec<f32>> {
    prop::collection::vec(f32s(), n)
}

/// `n` optional floats.
fn opt_floats(n: usize) -> impl Strategy<Value = Vec<Option<f32>>> {
    prop::collection::vec(opt_f32s(), n)
}

/// Hands out drawn values in order.
struct Take<T>(std::vec::IntoIter<T>);

impl<T> Take<T> {
    fn new(values: Vec<T>) -> Self {
        Self(values.into_iter())
    }
    fn next(&mut self) -> T {
        self.0.next().expect("enough values drawn")
    }
    fn arr<const N: usize>(&mut self) -> [T; N] {
        std::array::from_fn(|_| self.next())
    }
}

/// Integers with their varint boundaries often.
fn u16s() -> BoxedStrategy<u16> {
    prop_oneof![
        3 => any::<u16>(),
        1 => prop::sample::select(vec![0u16, 1, 127, 128, 16_383, 16_384, u16::MAX - 1, u16::MAX]),
    ]
    .boxed()
}

fn u32s() -> BoxedStrategy<u32> {
    prop_oneof![
        3 => any::<u32>(),
        1 => prop::sample::select(vec![0u32, 127, 128, 16_384, 1 << 21, 1 << 28, u32::MAX]),
    ]
    .boxed()
}

fn i16s() -> BoxedStrategy<i16> {
    prop_oneof![
        3 => any::<i16>(),
        1 => prop::sample::select(vec![0i16, -1, 63, -64, 64, -65, 8191, -8192, 8192, i16::MIN, i16::MAX]),
    ]
    .boxed()
}

fn units<T: DeserializeOwned + Clone + Debug + 'static>() -> BoxedStrategy<T> {
    prop::sample::select(all_units::<T>()).boxed()
}

/// A heapless vector of any length up to `N`, often empty, full or one short.
fn hvec<T, const N: usize>(element: BoxedStrategy<T>) -> BoxedStrategy<heapless::Vec<T, N>>
where
    T: Clone + Debug + 'static,
{
    prop_oneof![Just(0usize), Just(N), Just(N - 1), 0..=N]
        .prop_flat_map(move |len| prop::collection::vec(element.clone(), len))
        .prop_map(|v| heapless::Vec::from_slice(&v).expect("within capacity"))
        .boxed()
}

/// A heapless string of up to `N` bytes: empty, full of ASCII, full of two-byte
/// characters, or any characters (NUL and astral ones included) while they fit.
fn hstring<const N: usize>() -> BoxedStrategy<heapless::String<N>> {
    let fill = |text: String| {
        let mut s = heapless::String::<N>::new();
        for c in text.chars() {
            if s.push(c).is_err() {
                break;
            }
        }
        s
    };
    prop_oneof![
        Just(String::new()),
        prop::collection::vec(0x20u8..0x7f, N).prop_map(|b| String::from_utf8(b).unwrap()),
        Just("é".repeat(N / 2)),
        prop::collection::vec(any::<char>(), 0..=N).prop_map(|c| c.into_iter().collect()),
    ]
    .prop_map(fill)
    .boxed()
}

fn core_errors() -> BoxedStrategy<CoreError> {
    prop_oneof![
        units::<Field>().prop_map(|field| CoreError::NotFinite { field }),
        (units::<Field>(), f32s())
            .prop_map(|(field, value)| CoreError::OutOfRange { field, value }),
        Just(CoreError::NumericalFailure),
        Just(CoreError::ModelLeftOut),
        (u16s(), f32s()).prop_map(|(events, time)| CoreError::Unfinished { events, time }),
        (units::<Tier>(), units::<Reason>(), f32s()).prop_map(|(model, reason, value)| {
            CoreError::OutsideValidity {
                model,
                reason,
                value,
            }
        }),
    ]
    .boxed()
}

fn frame_faults() -> BoxedStrategy<FrameFault> {
    prop_oneof![
        Just(FrameFault::Cobs),
        u32s().prop_map(|length| FrameFault::Oversized { length }),
        u16s().prop_map(|length| FrameFault::Short { length }),
        u16s().prop_map(|seq_as_read| FrameFault::Crc { seq_as_read }),
        Just(FrameFault::Undecodable),
        u16s().prop_map(|count| FrameFault::TrailingBytes { count }),
    ]
    .boxed()
}

fn sequence_faults() -> BoxedStrategy<SequenceFault> {
    prop_oneof![
        u16s().prop_map(|seq| SequenceFault::Duplicate { seq }),
        (u16s(), u16s()).prop_map(|(seq, expected)| SequenceFault::Stale { seq, expected }),
        (u16s(), u16s()).prop_map(|(seq, expected)| SequenceFault::Gap { seq, expected }),
    ]
    .boxed()
}

fn stroke_errors() -> BoxedStrategy<StrokeError> {
    let counts = u32s;
    prop_oneof![
        units::<ConfigField>().prop_map(StrokeError::InvalidConfig),
        (counts(), counts()).prop_map(|(len, min)| StrokeError::TooShort { len, min }),
        counts().prop_map(|index| StrokeError::NotFinite { index }),
        Just(StrokeError::NotAtRest),
        Just(StrokeError::NoImpact),
        counts().prop_map(|index| StrokeError::Saturated { index }),
        f32s().prop_map(|speed| StrokeError::NotForward { speed }),
        (counts(), counts())
            .prop_map(|(accel, pitch)| StrokeError::LengthMismatch { accel, pitch }),
        core_errors().prop_map(StrokeError::Strike),
    ]
    .boxed()
}

fn upload_faults() -> BoxedStrategy<UploadFault> {
    prop_oneof![
        (u16s(), u16s()).prop_map(|(stroke, chunk)| UploadFault::NotStarted { stroke, chunk }),
        (u16s(), u16s(), u16s()).prop_map(|(stroke, expected, chunk)| UploadFault::Missing {
            stroke,
            expected,
            chunk
        }),
        (u16s(), u16s()).prop_map(|(stroke, chunk)| UploadFault::Duplicate { stroke, chunk }),
        (u16s(), u16s(), u16s()).prop_map(|(stroke, count, expected)| {
            UploadFault::CountChanged {
                stroke,
                count,
                expected,
            }
        }),
        (u16s(), u16s()).prop_map(|(chunk, count)| UploadFault::BadChunk { chunk, count }),
        (u16s(), u16s()).prop_map(|(stroke, chunk)| UploadFault::Empty { stroke, chunk }),
        (u16s(), u16s()).prop_map(|(stroke, chunk)| UploadFault::Overflow { stroke, chunk }),
        u16s().prop_map(|stroke| UploadFault::NoSetup { stroke }),
        (u16s(), u16s(), u16s(), units::<GlitchKind>(), i16s()).prop_map(
            |(stroke, chunk, sample, kind, value)| UploadFault::Glitch {
                stroke,
                chunk,
                sample,
                kind,
                value
            }
        ),
    ]
    .boxed()
}

fn link_errors() -> BoxedStrategy<LinkError> {
    prop_oneof![
        1 => frame_faults().prop_map(LinkError::Frame),
        1 => (u32s(), u32s()).prop_map(|(device, host)| LinkError::SchemaMismatch { device, host }),
        1 => sequence_faults().prop_map(LinkError::Sequence),
        3 => core_errors().prop_map(LinkError::Invalid),
        1 => Just(LinkError::SpinAndRoll),
        1 => Just(LinkError::MissingAim),
        1 => units::<Unsupported>().prop_map(LinkError::Unsupported),
        1 => units::<NoAim>().prop_map(LinkError::NoAim),
        1 => stroke_errors().prop_map(LinkError::Stroke),
        1 => upload_faults().prop_map(LinkError::Upload),
        1 => Just(LinkError::AnswerTooLarge),
    ]
    .boxed()
}

fn collides() -> BoxedStrategy<Collide> {
    (
        floats(2),
        prop::option::of(floats(3)),
        any::<bool>(),
        opt_floats(7),
        prop::option::of(units::<ModelName>()),
    )
        .prop_map(|(f, spin, roll, o, model)| {
            let mut f = Take::new(f);
            let mut o = Take::new(o);
            Collide {
                speed: f.next(),
                cut: f.next(),
                spin: spin.map(|s| Take::new(s).arr()),
                roll,
                mu: o.next(),
                mu_b: o.next(),
                mu_c: o.next(),
                restitution: o.next(),
                mu_s: o.next(),
                radius: o.next(),
                mass: o.next(),
                model,
            }
        })
        .boxed()
}

fn overrides() -> BoxedStrategy<Overrides> {
    (opt_floats(7), prop::option::of(units::<ModelName>()))
        .prop_map(|(o, model)| {
            let mut o = Take::new(o);
            Overrides {
                mu: o.next(),
                mu_b: o.next(),
                mu_c: o.next(),
                restitution: o.next(),
                mu_s: o.next(),
                radius: o.next(),
                mass: o.next(),
                model,
            }
        })
        .boxed()
}

fn stroke_setups() -> BoxedStrategy<StrokeSetup> {
    (
        f32s(),
        opt_f32s(),
        prop::option::of(floats(2)),
        opt_f32s(),
        opt_f32s(),
    )
        .prop_map(
            |(rate_hz, scale, tip, cue_mass, tip_restitution)| StrokeSetup {
                rate_hz,
                scale,
                tip_offset: tip.map(|t| Take::new(t).arr()),
                cue_mass,
                tip_restitution,
            },
        )
        .boxed()
}

fn stroke_chunks() -> BoxedStrategy<StrokeChunk> {
    (
        u16s(),
        u16s(),
        u16s(),
        hvec::<i16, MAX_SAMPLES>(i16s()),
        prop::option::of(stroke_setups()),
    )
        .prop_map(|(stroke, index, count, samples, setup)| StrokeChunk {
            stroke,
            index,
            count,
            samples,
            setup,
        })
        .boxed()
}

fn shot_requests() -> BoxedStrategy<ShotRequest> {
    (
        units::<TableName>(),
        floats(5),
        hvec::<[f32; 2], MAX_OBJECT_BALLS>(floats(2).prop_map(|f| Take::new(f).arr()).boxed()),
        opt_floats(11),
        prop::option::of(u16s()),
        prop::option::of(u16s()),
        prop::option::of(units::<ModelName>()),
    )
        .prop_map(|(table, f, balls, o, object, pocket, model)| {
            let mut f = Take::new(f);
            let mut o = Take::new(o);
            ShotRequest {
                table,
                cue: f.arr(),
                balls,
                speed: f.next(),
                tip: f.arr(),
                aim: o.next(),
                object,
                pocket,
                mu_cloth: o.next(),
                mu_roll: o.next(),
                cue_mass: o.next(),
                tip_restitution: o.next(),
                mu: o.next(),
                mu_b: o.next(),
                mu_c: o.next(),
                restitution: o.next(),
                mu_s: o.next(),
                mass: o.next(),
                model,
            }
        })
        .boxed()
}

fn requests() -> BoxedStrategy<Request> {
    prop_oneof![
        Just(Request::Version(Empty {})),
        collides().prop_map(Request::Collide),
        overrides().prop_map(Request::Params),
        stroke_chunks().prop_map(Request::Stroke),
        shot_requests().prop_map(Request::Shot),
        prop::option::of(shot_requests()).prop_map(Request::Plan),
        Just(Request::Shutdown(Empty {})),
    ]
    .boxed()
}

fn version_answers() -> BoxedStrategy<VersionAnswer> {
    (
        u32s(),
        hstring::<NAME_LEN>(),
        hstring::<NAME_LEN>(),
        (u16s(), u16s(), u16s()),
        any::<bool>(),
    )
        .prop_map(
            |(schema, firmware, board, (max_frame, max_samples, stroke_capacity), shot)| {
                VersionAnswer {
                    schema,
                    firmware,
                    board,
                    max_frame,
                    max_samples,
                    stroke_capacity,
                    shot,
                }
            },
        )
        .boxed()
}

fn ball_answer(f: &mut Take<f32>) -> BallAnswer {
    BallAnswer {
        v: f.arr(),
        w: f.arr(),
    }
}

fn collide_answers() -> BoxedStrategy<CollideAnswer> {
    (
        units::<ModelName>(),
        units::<RegimeName>(),
        any::<bool>(),
        floats(32),
    )
        .prop_map(|(model, regime, roll, f)| {
            let mut f = Take::new(f);
            CollideAnswer {
                model,
                regime,
                input: InputEcho {
                    speed: f.next(),
                    cut_deg: f.next(),
                    spin: f.arr(),
                    roll,
                    mu: f.next(),
                    mu_b: f.next(),
                    mu_c: f.next(),
                    restitution: f.next(),
                    mu_s: f.next(),
                    radius: f.next(),
                    mass: f.next(),
                },
                cue: ball_answer(&mut f),
                object: ball_answer(&mut f),
                throw_deg: f.next(),
                cue_deflection_deg: f.next(),
                separation_deg: f.next(),
                impulses: ImpulsesAnswer {
                    normal: f.next(),
                    friction: f.arr(),
                    table_friction: f.next(),
                },
            }
        })
        .boxed()
}

fn params_answers() -> BoxedStrategy<ParamsAnswer> {
    (floats(7), units::<ModelName>())
        .prop_map(|(f, model)| {
            let mut f = Take::new(f);
            ParamsAnswer {
                mu: f.next(),
                mu_b: f.next(),
                mu_c: f.next(),
                restitution: f.next(),
                mu_s: f.next(),
                radius: f.next(),
                mass: f.next(),
                model,
            }
        })
        .boxed()
}

fn stroke_progress() -> BoxedStrategy<StrokeProgress> {
    (u16s(), u16s(), u16s(), u16s())
        .prop_map(|(stroke, chunks, count, samples)| StrokeProgress {
            stroke,
            chunks,
            count,
            samples,
        })
        .boxed()
}

fn stroke_answers() -> BoxedStrategy<StrokeAnswer> {
    (u16s(), u16s(), u16s(), floats(7))
        .prop_map(|(stroke, samples, impact_index, f)| {
            let mut f = Take::new(f);
            StrokeAnswer {
                stroke,
                cue_speed: f.next(),
                ball_speed: f.next(),
                ball_spin: f.arr(),
                samples,
                impact_index,
                stroke_duration: f.next(),
                rest_noise: f.next(),
            }
        })
        .boxed()
}

fn solve_parts() -> BoxedStrategy<SolvePart> {
    (u16s(), u16s(), any::<bool>(), u32s(), floats(11))
        .prop_map(|(object, pocket, thinner, evaluations, f)| {
            let mut f = Take::new(f);
            SolvePart {
                object,
                pocket,
                aim_deg: f.next(),
                naive_aim_deg: f.next(),
                correction_deg: f.next(),
                correction_offset: f.next(),
                thinner,
                cut_deg: f.next(),
                ghost_ball: f.arr(),
                naive_ghost_ball: f.arr(),
                evaluations,
                residual: f.next(),
            }
        })
        .boxed()
}

fn contact_parts() -> BoxedStrategy<ContactPart> {
    (
        u16s(),
        floats(11),
        (units::<ModelName>(), units::<ModelName>()),
        opt_f32s(),
        units::<RegimeName>(),
    )
        .prop_map(|(ball, f, (model, model_used), error_estimate, regime)| {
            let mut f = Take::new(f);
            ContactPart {
                ball,
                time: f.next(),
                cue_position: f.arr(),
                line_of_centres: f.arr(),
                cut_deg: f.next(),
                speed: f.next(),
                spin: f.arr(),
                model,
                model_used,
                error_estimate,
                regime,
                throw_deg: f.next(),
            }
        })
        .boxed()
}

fn ball_parts() -> BoxedStrategy<BallPart> {
    (
        u16s(),
        floats(26),
        units::<EndName>(),
        prop::option::of(u16s()),
    )
        .prop_map(|(ball, f, end, pocket)| {
            let mut f = Take::new(f);
            BallPart {
                ball,
                start: f.arr(),
                velocity: f.arr(),
                spin: f.arr(),
                hop_height: f.next(),
                air_time: f.next(),
                landing: f.arr(),
                sliding_time: f.next(),
                rolling_start: f.arr(),
                rolling_velocity: f.arr(),
                rolling_speed: f.next(),
                rolling_direction_deg: f.next(),
                stop_time: f.next(),
                rest: f.arr(),
                end,
                end_time: f.next(),
                end_position: f.arr(),
                pocket,
            }
        })
        .boxed()
}

fn target_parts() -> BoxedStrategy<TargetPart> {
    (u16s(), u16s(), any::<bool>(), opt_f32s())
        .prop_map(|(object, pocket, pocketed, miss)| TargetPart {
            object,
            pocket,
            pocketed,
            miss,
        })
        .boxed()
}

fn shot_answers() -> BoxedStrategy<ShotAnswer> {
    (
        units::<ShotMode>(),
        floats(12),
        prop::option::of(solve_parts()),
        prop::option::of(contact_parts()),
        ball_parts(),
        prop::option::of(ball_parts()),
        prop::option::of(target_parts()),
    )
        .prop_map(|(mode, f, solve, contact, cue_ball, object_ball, target)| {
            let mut f = Take::new(f);
            ShotAnswer {
                mode,
                stroke: StrokePart {
                    cue_speed: f.next(),
                    tip: f.arr(),
                    aim_deg: f.next(),
                    aim: f.arr(),
                    launch_speed: f.next(),
                    launch_spin: f.arr(),
                },
                solve,
                contact,
                cue_ball,
                object_ball,
                target,
            }
        })
        .boxed()
}

fn u64s() -> BoxedStrategy<u64> {
    prop_oneof![
        3 => any::<u64>(),
        1 => prop::sample::select(vec![0u64, 127, 128, 1 << 35, u64::MAX]),
    ]
    .boxed()
}

fn stream_faults() -> BoxedStrategy<StreamFault> {
    prop_oneof![
        u64s().prop_map(|index| StreamFault::NotAtRest { index }),
        (u64s(), u64s()).prop_map(|(first, second)| StreamFault::DoubleHit { first, second }),
        (u64s(), u64s()).prop_map(|(index, impact)| StreamFault::Saturated { index, impact }),
        (u64s(), f32s()).prop_map(|(impact, speed)| StreamFault::NotForward { impact, speed }),
        u64s().prop_map(|index| StreamFault::NotFinite { index }),
        (u64s(), u64s())
            .prop_map(|(rest_end, samples)| StreamFault::EndedMidStroke { rest_end, samples }),
    ]
    .boxed()
}

fn live_reports() -> BoxedStrategy<LiveReport> {
    let strokes = (
        (u32s(), u64s(), f32s(), u32s()),
        floats(7),
        prop::option::of(f32s()),
        prop::option::of(prop_oneof![
            shot_answers().prop_map(Ok),
            link_errors().prop_map(Err)
        ]),
    )
        .prop_map(
            |((stroke, impact_sample, cue_speed, latency), f, tempo, guidance)| {
                let mut f = Take::new(f);
                LiveReport::Stroke(LiveStroke {
                    stroke,
                    impact_sample,
                    cue_speed,
                    latency_instructions: latency,
                    metrics: StrokeMetrics {
                        backswing_length: f.next(),
                        backswing_time: f.next(),
                        pause: f.next(),
                        forward_time: f.next(),
                        tempo,
                        accel_at_impact: f.next(),
                        elevation_change_deg: f.next(),
                        wobble_dps: f.next(),
                    },
                    guidance,
                })
            },
        );
    prop_oneof![
        2 => strokes,
        1 => stream_faults().prop_map(LiveReport::Fault),
        1 => prop_oneof![
            u64s().prop_map(|sample| SensorFault::ReadFailed { sample }),
            u64s().prop_map(|sample| SensorFault::Stalled { sample }),
            Just(SensorFault::NotStarted),
        ]
        .prop_map(LiveReport::Sensor),
        1 => (u64s(), any::<bool>(), u64s(), u32s(), u32s()).prop_map(
            |(samples, truncated, work, max, resolve_max)| {
                LiveReport::TraceEnd(TraceEnd {
                    samples,
                    truncated,
                    work_instructions: work,
                    work_max_instructions: max,
                    resolve_max_instructions: resolve_max,
                })
            }
        ),
        1 => (u32s(), f32s(), f32s()).prop_map(|(stroke, length, time)| {
            LiveReport::FollowThrough(FollowThrough {
                stroke,
                length,
                time,
            })
        }),
    ]
    .boxed()
}

fn responses() -> BoxedStrategy<Response> {
    prop_oneof![
        1 => version_answers().prop_map(Response::Version),
        1 => collide_answers().prop_map(Response::Collide),
        1 => params_answers().prop_map(Response::Params),
        1 => stroke_progress().prop_map(Response::StrokeChunk),
        1 => stroke_answers().prop_map(Response::Stroke),
        1 => shot_answers().prop_map(Response::Shot),
        1 => any::<bool>().prop_map(Response::Plan),
        2 => live_reports().prop_map(Response::Live),
        1 => (u32s(), u32s())
            .prop_map(|(requests, errors)| Response::Shutdown(ShutdownAnswer { requests, errors })),
        // The errors have the most variants (and `Field`'s 33 under `Invalid`).
        4 => link_errors().prop_map(Response::Error),
    ]
    .boxed()
}

// ---------------------------------------------------------------------------------------
// The tests.

proptest! {
    #![proptest_config(ProptestConfig::with_cases(10_000))]

    #[test]
    fn every_request_round_trips(request in requests(), seq in u16s()) {
        round_trip(&request, seq);
    }

    #[test]
    fn every_answer_round_trips(response in responses(), seq in u16s()) {
        round_trip(&response, seq);
    }
}

/// Every enum of the schema, with every variant, read from the types.
fn schema_enums() -> BTreeSet<(&'static str, &'static str)> {
    let lists = [
        probe::variants::<Request>(),
        probe::variants::<Response>(),
        probe::variants::<LinkError>(),
        probe::variants::<FrameFault>(),
        probe::variants::<SequenceFault>(),
        probe::variants::<Unsupported>(),
        probe::variants::<NoAim>(),
        probe::variants::<StrokeError>(),
        probe::variants::<ConfigField>(),
        probe::variants::<UploadFault>(),
        probe::variants::<GlitchKind>(),
        probe::variants::<CoreError>(),
        probe::variants::<Field>(),
        probe::variants::<Tier>(),
        probe::variants::<Reason>(),
        probe::variants::<ModelName>(),
        probe::variants::<RegimeName>(),
        probe::variants::<TableName>(),
        probe::variants::<EndName>(),
        probe::variants::<ShotMode>(),
        probe::variants::<LiveReport>(),
        probe::variants::<SensorFault>(),
        probe::variants::<StreamFault>(),
        probe::variants::<Result<(), ()>>(),
    ];
    lists
        .iter()
        .flat_map(|(ty, names)| names.iter().map(move |name| (*ty, *name)))
        .collect()
}

/// What the drawn values covered: enum variants, `Some` and `None`, sequence and string
/// lengths.
#[derive(Default)]
struct Coverage {
    variants: BTreeSet<(&'static str, &'static str)>,
    some: usize,
    none: usize,
    seq_lengths: BTreeSet<usize>,
    str_lengths: BTreeSet<usize>,
    nan: usize,
    negative_zero: usize,
    subnormal: usize,
    infinite: usize,
}

impl Coverage {
    fn add(&mut self, tokens: &[tokens::Tok]) {
        use tokens::Tok;
        for tok in tokens {
            match tok {
                Tok::Variant { ty, name, .. } => {
                    self.variants.insert((ty, name));
                }
                Tok::Some => self.some += 1,
                Tok::None => self.none += 1,
                Tok::Seq(Some(len)) => {
                    self.seq_lengths.insert(*len);
                }
                Tok::Str(s) => {
                    self.str_lengths.insert(s.len());
                }
                Tok::F32(bits) => {
                    let x = f32::from_bits(*bits);
                    self.nan += usize::from(x.is_nan());
                    self.negative_zero += usize::from(*bits == 0x8000_0000);
                    self.subnormal += usize::from(x.is_subnormal());
                    self.infinite += usize::from(x.is_infinite());
                }
                _ => {}
            }
        }
    }
}

/// Draws `cases` values of `strategy` (deterministically) into `coverage`.
fn draw<T: Serialize + Debug>(strategy: BoxedStrategy<T>, cases: usize, coverage: &mut Coverage) {
    let mut runner = TestRunner::new_with_rng(
        Config::default(),
        proptest::test_runner::TestRng::deterministic_rng(
            proptest::test_runner::RngAlgorithm::ChaCha,
        ),
    );
    for _ in 0..cases {
        let value = strategy.new_tree(&mut runner).expect("a value").current();
        coverage.add(&tokens::of(&value));
    }
}

#[test]
fn strategies_reach_every_variant() {
    let mut coverage = Coverage::default();
    draw(requests(), 5_000, &mut coverage);
    draw(responses(), 20_000, &mut coverage);
    let expected = schema_enums();
    let missing: Vec<_> = expected.difference(&coverage.variants).collect();
    assert!(missing.is_empty(), "never drawn: {missing:?}");
    let unknown: Vec<_> = coverage.variants.difference(&expected).collect();
    assert!(
        unknown.is_empty(),
        "drawn but not in schema_enums (add the enum there): {unknown:?}"
    );
    let enums: BTreeSet<_> = expected.iter().map(|(ty, _)| ty).collect();
    println!(
        "all {} variants of the schema's {} enums drawn (25,000 values)",
        expected.len(),
        enums.len()
    );
    cuesight_figures::record!("link-schema-variants", "{}", expected.len());
    cuesight_figures::record!("link-schema-enums", "{}", enums.len());
    assert!(coverage.some > 1000 && coverage.none > 1000);
    for len in [0, MAX_SAMPLES, MAX_SAMPLES - 1, MAX_OBJECT_BALLS] {
        assert!(coverage.seq_lengths.contains(&len), "no sequence of {len}");
    }
    for len in [0, NAME_LEN] {
        assert!(
            coverage.str_lengths.contains(&len),
            "no string of {len} bytes"
        );
    }
    assert!(coverage.nan > 100, "{} NaNs", coverage.nan);
    assert!(coverage.negative_zero > 10, "{} −0", coverage.negative_zero);
    assert!(coverage.subnormal > 10, "{} subnormals", coverage.subnormal);
    assert!(coverage.infinite > 10, "{} infinities", coverage.infinite);
}

/// The bit-for-bit comparison is what it claims: it tells NaN payloads and the zeros'
/// signs apart, which `PartialEq` does not.
#[test]
fn the_comparison_sees_bits() {
    let a = Request::Collide(Collide::new(f32::NAN, 0.0));
    let b = Request::Collide(Collide::new(f32::from_bits(0x7fc1_2345), 0.0));
    let c = Request::Collide(Collide::new(f32::NAN, -0.0));
    assert_eq!(tokens::of(&a), tokens::of(&a.clone()));
    assert_ne!(tokens::of(&a), tokens::of(&b));
    assert_ne!(tokens::of(&a), tokens::of(&c));
    assert_ne!(a, a.clone(), "PartialEq: NaN is not NaN");
}

/// The largest message of each kind fits a frame: every option present, every vector
/// and string full, every varint at its longest, every sample three bytes.
#[test]
fn the_largest_messages_fit() {
    let big = f32::from_bits(0xffff_ffff);
    let stroke = Request::Stroke(StrokeChunk {
        stroke: u16::MAX,
        index: u16::MAX,
        count: u16::MAX,
        samples: heapless::Vec::from_slice(&[i16::MIN; MAX_SAMPLES]).unwrap(),
        setup: Some(StrokeSetup {
            rate_hz: big,
            scale: Some(big),
            tip_offset: Some([big; 2]),
            cue_mass: Some(big),
            tip_restitution: Some(big),
        }),
    });
    let shot = Request::Shot(ShotRequest {
        table: TableName::Snooker,
        cue: [big; 2],
        balls: heapless::Vec::from_slice(&[[big; 2]; MAX_OBJECT_BALLS]).unwrap(),
        speed: big,
        tip: [big; 2],
        aim: Some(big),
        object: Some(u16::MAX),
        pocket: Some(u16::MAX),
        mu_cloth: Some(big),
        mu_roll: Some(big),
        cue_mass: Some(big),
        tip_restitution: Some(big),
        mu: Some(big),
        mu_b: Some(big),
        mu_c: Some(big),
        restitution: Some(big),
        mu_s: Some(big),
        mass: Some(big),
        model: Some(ModelName::Reference),
    });
    let name: heapless::String<NAME_LEN> = "\u{10ffff}".repeat(NAME_LEN / 4).parse().unwrap();
    let version = Response::Version(VersionAnswer {
        schema: u32::MAX,
        firmware: name.clone(),
        board: name,
        max_frame: u16::MAX,
        max_samples: u16::MAX,
        stroke_capacity: u16::MAX,
        shot: true,
    });
    let ball = BallPart {
        ball: u16::MAX,
        start: [big; 2],
        velocity: [big; 3],
        spin: [big; 3],
        hop_height: big,
        air_time: big,
        landing: [big; 2],
        sliding_time: big,
        rolling_start: [big; 2],
        rolling_velocity: [big; 2],
        rolling_speed: big,
        rolling_direction_deg: big,
        stop_time: big,
        rest: [big; 2],
        end: EndName::Cushion,
        end_time: big,
        end_position: [big; 2],
        pocket: Some(u16::MAX),
    };
    let answer = Response::Shot(ShotAnswer {
        mode: ShotMode::Solve,
        stroke: StrokePart {
            cue_speed: big,
            tip: [big; 2],
            aim_deg: big,
            aim: [big; 2],
            launch_speed: big,
            launch_spin: [big; 3],
        },
        solve: Some(SolvePart {
            object: u16::MAX,
            pocket: u16::MAX,
            aim_deg: big,
            naive_aim_deg: big,
            correction_deg: big,
            correction_offset: big,
            thinner: true,
            cut_deg: big,
            ghost_ball: [big; 2],
            naive_ghost_ball: [big; 2],
            evaluations: u32::MAX,
            residual: big,
        }),
        contact: Some(ContactPart {
            ball: u16::MAX,
            time: big,
            cue_position: [big; 2],
            line_of_centres: [big; 2],
            cut_deg: big,
            speed: big,
            spin: [big; 3],
            model: ModelName::Reference,
            model_used: ModelName::Reference,
            error_estimate: Some(big),
            regime: RegimeName::Gripping,
            throw_deg: big,
        }),
        cue_ball: ball,
        object_ball: Some(ball),
        target: Some(TargetPart {
            object: u16::MAX,
            pocket: u16::MAX,
            pocketed: true,
            miss: Some(big),
        }),
    });
    for request in [&stroke, &shot] {
        round_trip(request, u16::MAX);
    }
    for response in [&version, &answer] {
        round_trip(response, u16::MAX);
    }
}

/// COBS at its corners: raw frames of every length up to [`MAX_RAW`] (bodies of raw
/// bytes, a `Vec<u8>` in postcard), without zeros (so full 254-byte blocks, and a frame
/// ending exactly at one), all zeros, and mixed; one byte more than fits is refused.
#[test]
fn frames_of_every_length_round_trip() {
    // Body = length varint (2 bytes from 128 on) + bytes; raw = 6 + body + 4.
    let room = |len: usize| 6 + if len < 128 { 1 } else { 2 } + len + 4;
    let mut longest = 0;
    for len in 0..=MAX_RAW {
        if room(len) > MAX_RAW {
            let mut wire = [0u8; MAX_FRAME];
            let refused = frame::encode(SCHEMA_HASH, 1, &vec![1u8; len], &mut wire);
            assert_eq!(refused, Err(LinkError::AnswerTooLarge), "{len} bytes");
            break;
        }
        longest = len;
        for body in [
            vec![0x01u8; len],
            vec![0xffu8; len],
            vec![0u8; len],
            (0..len).map(|i| (i % 256) as u8).collect::<Vec<u8>>(),
        ] {
            // Schema and seq without a zero byte, and with.
            round_trip_as(0x0101_0101, 0x0101, &body);
            round_trip(&body, 0);
        }
    }
    assert_eq!(room(longest), MAX_RAW, "the longest body fills a raw frame");
}

/// [`round_trip`] for a foreign schema hash.
fn round_trip_as(schema: u32, seq: u16, body: &Vec<u8>) {
    let mut wire = [0u8; MAX_FRAME];
    let len = frame::encode(schema, seq, body, &mut wire).expect("fits");
    let wire = &wire[..len];
    check_wire(wire);
    let mut reader = FrameReader::new();
    let mut frames = Vec::new();
    for &byte in wire {
        if let Some(received) = reader.push(byte) {
            frames.push(match received {
                Received::Frame(raw) => raw.to_vec(),
                Received::Fault(fault) => panic!("{fault:?} for {} bytes", body.len()),
            });
        }
    }
    assert_eq!(frames.len(), 1);
    let (header, opened) = frame::open(&frames[0]).expect("opens");
    assert_eq!((header.schema, header.seq), (schema, seq));
    assert_eq!(&frame::decode::<Vec<u8>>(opened).expect("decodes"), body);
    let (s, q, host) = reference_decode::<Vec<u8>>(wire);
    assert_eq!((s, q, &host), (schema, seq, body));
}
