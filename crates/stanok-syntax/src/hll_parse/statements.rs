//! Statements of the AxiOMA high-level language: the items of one line (declarations,
//! expression statements, the headers of `if`/`else`/`for`/`while`/`do`, braces), each ending
//! as C requires (`;` after statements, `( … )` around conditions). See the parent module.

use super::{Parser, Tok, R};
use crate::ast::{ColSpan, Comment, CommentKind};
use crate::hll::{HDecl, HExprId, HInit, HItem, HType};
use crate::lexer::find;

impl Parser<'_> {
    /// All items of the line.
    pub(super) fn items(&mut self) -> R<()> {
        while self.tok != Tok::End {
            let start = self.span.start as usize;
            let item = self.item()?;
            let span = ColSpan::new(start, self.last_end.max(start));
            self.out.hll_mut().items.push((item, span));
        }
        Ok(())
    }

    fn ty(&self) -> Option<HType> {
        if self.tok != Tok::Ident {
            return None;
        }
        Some(match self.text(self.span) {
            b"int" => HType::Int,
            b"long" => HType::Long,
            b"double" | b"float" => HType::Double,
            b"bool" => HType::Bool,
            b"string" => HType::String,
            _ => return None,
        })
    }

    fn item(&mut self) -> R<HItem> {
        if let Tok::Punct(p @ ("{" | "}" | ";")) = self.tok {
            self.advance();
            return Ok(match p {
                "{" => HItem::Open,
                "}" => HItem::Close,
                _ => HItem::Empty,
            });
        }
        if self.is_kw("const") {
            self.advance();
            if self.ty().is_none() {
                return self.expected("a type after `const`").map(|_| HItem::Empty);
            }
        }
        if self.ty().is_some() {
            let d = self.declaration()?;
            self.eat(";")?;
            return Ok(d);
        }
        if self.tok == Tok::Ident {
            let span = self.span;
            match self.text(span) {
                b"if" => {
                    self.advance();
                    return Ok(HItem::If(self.condition()?));
                }
                b"else" => {
                    self.advance();
                    return Ok(HItem::Else);
                }
                b"do" => {
                    self.advance();
                    return Ok(HItem::Do);
                }
                b"while" => {
                    self.advance();
                    let cond = self.condition()?;
                    let terminated = self.is(";");
                    if terminated {
                        self.advance();
                    }
                    return Ok(HItem::While { cond, terminated });
                }
                b"for" => return self.for_header(),
                b"break" | b"continue" => {
                    let brk = self.text(span) == b"break";
                    self.advance();
                    self.eat(";")?;
                    return Ok(if brk { HItem::Break } else { HItem::Continue });
                }
                w @ (b"switch" | b"case" | b"default" | b"goto" | b"return" | b"struct"
                | b"void" | b"char" | b"unsigned" | b"signed" | b"short" | b"define") => {
                    let w = String::from_utf8_lossy(w).into_owned();
                    self.error(
                        "hll::unsupported",
                        format!("`{w}` is not part of Stanok's AxiOMA high-level language"),
                        span,
                    );
                    return Err(());
                }
                _ => {}
            }
        }
        let e = self.expr()?;
        self.eat(";")?;
        Ok(HItem::Expr(e))
    }

    fn condition(&mut self) -> R<HExprId> {
        self.eat("(")?;
        let c = self.expr()?;
        self.eat(")")?;
        Ok(c)
    }

    fn declaration(&mut self) -> R<HItem> {
        let ty = self.ty().unwrap_or(HType::Double);
        self.advance();
        let mut vars = Vec::new();
        loop {
            if self.tok != Tok::Ident || self.ty().is_some() {
                return self.expected("a variable name").map(|_| HItem::Empty);
            }
            let name = self.span;
            self.advance();
            let mut len = None;
            if self.is("[") {
                self.advance();
                len = Some(self.expr()?);
                self.eat("]")?;
            }
            let mut init = HInit::None;
            if self.is("=") {
                self.advance();
                if self.is("{") {
                    self.advance();
                    let mut list = Vec::new();
                    while !self.is("}") {
                        list.push(self.expr()?);
                        if self.is(",") {
                            self.advance();
                        } else {
                            break;
                        }
                    }
                    self.eat("}")?;
                    init = HInit::List(list);
                } else {
                    init = HInit::Expr(self.expr()?);
                }
            }
            let span = ColSpan::new(name.start as usize, self.last_end);
            vars.push(HDecl {
                name,
                len,
                init,
                span,
            });
            if self.is(",") {
                self.advance();
                continue;
            }
            return Ok(HItem::Decl { ty, vars });
        }
    }

    fn for_header(&mut self) -> R<HItem> {
        self.advance();
        self.eat("(")?;
        let init = if self.is(";") {
            None
        } else if self.ty().is_some() {
            Some(Box::new(self.declaration()?))
        } else {
            Some(Box::new(HItem::Expr(self.expr()?)))
        };
        self.eat(";")?;
        let cond = if self.is(";") {
            None
        } else {
            Some(self.expr()?)
        };
        self.eat(";")?;
        let step = if self.is(")") {
            None
        } else {
            Some(self.expr()?)
        };
        self.eat(")")?;
        Ok(HItem::For { init, cond, step })
    }

    /// After an error: the rest of the line is skipped, but its comments still count (a `/*`
    /// there opens a multi-line comment).
    pub(super) fn skip_rest(&mut self, from: usize) {
        let b = self.b;
        let mut i = from;
        let mut in_string = false;
        while i < b.len() {
            match b[i] {
                b'"' => in_string = !in_string,
                b'\\' if in_string => i += 1,
                b'/' if !in_string && b.get(i + 1) == Some(&b'/') => {
                    self.out.comments.push(Comment {
                        kind: CommentKind::Line,
                        text: ColSpan::new(i + 2, b.len()),
                    });
                    return;
                }
                b'/' if !in_string && b.get(i + 1) == Some(&b'*') => match find(b, i + 2, b"*/") {
                    Some(q) => {
                        self.out.comments.push(Comment {
                            kind: CommentKind::Block,
                            text: ColSpan::new(i + 2, q),
                        });
                        i = q + 2;
                        continue;
                    }
                    None => {
                        self.out.comments.push(Comment {
                            kind: CommentKind::Block,
                            text: ColSpan::new(i + 2, b.len()),
                        });
                        *self.in_comment = true;
                        return;
                    }
                },
                _ => {}
            }
            i += 1;
        }
    }
}
