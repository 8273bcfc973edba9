//! The attributes of `wasp-kani-shim`: `#[kani::proof]` turns a harness
//! into a test that runs its body under the shim's explorer, and
//! `#[kani::unwind(N)]` is accepted and ignored (the shim runs real loops;
//! Kani needs the bound to unroll them).
//!
//! Written on `proc_macro` alone: a harness is `fn NAME() { BODY }` with
//! outer attributes and a visibility, which needs no parser crate.

use proc_macro::{Delimiter, Group, Ident, Literal, Punct, Spacing, Span, TokenStream, TokenTree};

/// `#[kani::proof] fn NAME() BODY` becomes
///
/// ```text
/// #[cfg_attr(test, test)] #[allow(dead_code)]
/// fn NAME() { ::kani::__shim::run_harness(module_path!(), "NAME", || BODY) }
/// ```
///
/// The body is the harness's own token tree, spans included, so an error
/// in it points at the harness. `allow(dead_code)`: outside `cargo test`
/// the harness and the helpers it calls are compiled but never called.
#[proc_macro_attribute]
pub fn proof(attr: TokenStream, item: TokenStream) -> TokenStream {
    if let Some(t) = attr.into_iter().next() {
        return error(t.span(), "`#[kani::proof]` takes no arguments");
    }
    match Harness::parse(item) {
        Ok(h) => h.expand(),
        Err((span, msg)) => error(span, msg),
    }
}

/// `#[kani::unwind(N)]`: checked to be one integer literal, then ignored.
#[proc_macro_attribute]
pub fn unwind(attr: TokenStream, item: TokenStream) -> TokenStream {
    let args: Vec<TokenTree> = attr.into_iter().collect();
    match args.as_slice() {
        [TokenTree::Literal(l)] if l.to_string().parse::<u64>().is_ok() => item,
        _ => error(
            Span::call_site(),
            "`#[kani::unwind(N)]` takes one integer literal",
        ),
    }
}

/// A harness split into the parts the expansion needs.
struct Harness {
    /// Outer attributes and visibility, before `fn`.
    prefix: Vec<TokenTree>,
    name: Ident,
    body: Group,
}

impl Harness {
    fn parse(item: TokenStream) -> Result<Self, (Span, &'static str)> {
        let tokens: Vec<TokenTree> = item.into_iter().collect();
        let fn_at = tokens
            .iter()
            .position(|t| matches!(t, TokenTree::Ident(i) if i.to_string() == "fn"))
            .ok_or((Span::call_site(), "`#[kani::proof]` goes on a function"))?;
        let rest = &tokens[fn_at + 1..];
        match rest {
            [TokenTree::Ident(name), TokenTree::Group(params), TokenTree::Group(body)]
                if params.delimiter() == Delimiter::Parenthesis
                    && body.delimiter() == Delimiter::Brace =>
            {
                if !params.stream().is_empty() {
                    return Err((params.span(), "a harness takes no parameters"));
                }
                Ok(Self {
                    prefix: tokens[..fn_at].to_vec(),
                    name: name.clone(),
                    body: body.clone(),
                })
            }
            _ => Err((
                tokens[fn_at].span(),
                "a harness is `fn NAME() { ... }`: no generics, return type or where clause",
            )),
        }
    }

    fn expand(self) -> TokenStream {
        let mut out: TokenStream = "#[cfg_attr(test, test)] #[allow(dead_code)]"
            .parse()
            .expect("attribute tokens");
        out.extend(self.prefix);
        out.extend([
            TokenTree::Ident(Ident::new("fn", Span::call_site())),
            TokenTree::Ident(self.name.clone()),
            TokenTree::Group(Group::new(Delimiter::Parenthesis, TokenStream::new())),
        ]);
        // ::kani::__shim::run_harness(::core::module_path!(), "NAME", || BODY);
        let mut args: TokenStream = "::core::module_path!(),".parse().expect("path tokens");
        args.extend([
            TokenTree::Literal(Literal::string(&self.name.to_string())),
            TokenTree::Punct(Punct::new(',', Spacing::Alone)),
            TokenTree::Punct(Punct::new('|', Spacing::Joint)),
            TokenTree::Punct(Punct::new('|', Spacing::Alone)),
            TokenTree::Group(self.body),
        ]);
        let mut call: TokenStream = "::kani::__shim::run_harness".parse().expect("call tokens");
        call.extend([
            TokenTree::Group(Group::new(Delimiter::Parenthesis, args)),
            TokenTree::Punct(Punct::new(';', Spacing::Alone)),
        ]);
        out.extend([TokenTree::Group(Group::new(Delimiter::Brace, call))]);
        out
    }
}

/// `compile_error!(msg)` at `span`.
fn error(span: Span, msg: &str) -> TokenStream {
    let mut t: TokenStream = "::core::compile_error!".parse().expect("macro tokens");
    let mut lit = Literal::string(msg);
    lit.set_span(span);
    let mut g = Group::new(Delimiter::Parenthesis, TokenTree::Literal(lit).into());
    g.set_span(span);
    t.extend([
        TokenTree::Group(g),
        TokenTree::Punct(Punct::new(';', Spacing::Alone)),
    ]);
    t
}
