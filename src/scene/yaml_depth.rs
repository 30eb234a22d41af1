//! How deeply a YAML document nests, found before it is deserialized.
//!
//! yaml_serde refuses documents nested deeper than 128 collections, but only once libyaml has
//! scanned the whole document into events, and libyaml's scanner does work in proportion to
//! the number of open flow collections (`[`, `{`) for every token: 80 000 `[` took 80 s. Here
//! the same parser is run one event at a time, counting open sequences and mappings (flow and
//! block alike, exactly as libyaml sees them: brackets inside quoted or block scalars and
//! comments are text), and it stops at the first collection past the limit, so the scan costs
//! at most the limit per token. A document libyaml cannot parse is left to yaml_serde, which
//! reports the syntax error at the same place.

use libyaml_rs as sys;
use std::mem::MaybeUninit;

/// The line (from 1) of the first collection of `text` nested deeper than `max`, if any.
pub(crate) fn first_too_deep(text: &str, max: usize) -> Option<u64> {
    // libyaml's parser keeps a pointer to itself (its string reader's data): boxed, never moved
    let mut parser: Box<MaybeUninit<sys::yaml_parser_t>> = Box::new(MaybeUninit::uninit());
    let p = parser.as_mut_ptr();
    // SAFETY: `p` points to a live allocation of a parser, initialised by
    // `yaml_parser_initialize` before any other call; the input outlives the parser (both end
    // with this function); `yaml_parser_delete` frees what it allocated, once.
    if unsafe { sys::yaml_parser_initialize(p) }.fail {
        return None;
    }
    unsafe {
        sys::yaml_parser_set_encoding(p, sys::YAML_UTF8_ENCODING);
        sys::yaml_parser_set_input_string(p, text.as_ptr(), text.len() as _);
    }
    let mut depth = 0usize;
    let mut found = None;
    loop {
        let mut event = MaybeUninit::<sys::yaml_event_t>::uninit();
        let e = event.as_mut_ptr();
        // SAFETY: on success `yaml_parser_parse` initialises the event, which is read and then
        // freed once; on failure there is no event to free.
        if unsafe { sys::yaml_parser_parse(p, e) }.fail {
            break;
        }
        let (kind, line) = unsafe { ((*e).type_, (*e).start_mark.line) };
        unsafe { sys::yaml_event_delete(e) };
        match kind {
            sys::YAML_SEQUENCE_START_EVENT | sys::YAML_MAPPING_START_EVENT => {
                depth += 1;
                if depth > max {
                    found = Some(line + 1);
                    break;
                }
            }
            sys::YAML_SEQUENCE_END_EVENT | sys::YAML_MAPPING_END_EVENT => {
                depth = depth.saturating_sub(1)
            }
            sys::YAML_STREAM_END_EVENT => break,
            _ => {}
        }
    }
    // SAFETY: initialised above, deleted once
    unsafe { sys::yaml_parser_delete(p) };
    found
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_flow_and_block_collections_but_not_brackets_in_text() {
        assert_eq!(first_too_deep("a: [[1]]", 3), None);
        assert_eq!(first_too_deep("a: [[1]]", 2), Some(1));
        assert_eq!(first_too_deep("a:\n  b:\n    - - x\n", 3), Some(3));
        assert_eq!(first_too_deep("a:\n  b:\n    - - x\n", 4), None);
        // quoted, block scalars and comments hold text, not collections
        let text = "a: '[[[['\nb: \"{{{{\"\nc: |\n  [[[[\n# [[[[\nd: x[[[[\n";
        assert_eq!(first_too_deep(text, 1), None);
        // a document that does not parse is left to the deserializer
        assert_eq!(first_too_deep("a: [", 5), None);
    }
}
