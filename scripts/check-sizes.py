#!/usr/bin/env python3
"""Checks the size limits of issue 25 on C++ sources: no file over
--max-file-lines lines and no function over --max-function-lines lines.

    scripts/check-sizes.py [--max-file-lines 400] [--max-function-lines 60] DIR...

Prints each file or function over its limit as `path:line: ...`, then the
longest function and the longest file it saw, and exits 1 when anything is
over, 2 when a file cannot be read as C++ (unbalanced braces).

A function spans from the first line of its declaration (its template
head, return type and name) to its closing brace; a lambda from its `[` to
its closing brace. A lambda inside a function is part of that function; a
lambda in a table at file or class scope is a function of its own, and the
table itself is not one. Comments, string and character literals (raw
strings included) and preprocessor lines are read past, so a brace inside
them counts for nothing. The reading is a brace matcher, not a compiler:
it needs no build and reads one file in milliseconds; it assumes code as
clang-format leaves it and no braces split across #if branches (it says so
when the braces of a file do not balance).
"""
import argparse
import os
import sys

CXX_SUFFIXES = ('.cpp', '.hpp', '.h', '.cc', '.hh', '.ipp', '.inc')
QUALIFIERS = {'const', 'override', 'final', 'noexcept', 'mutable', 'volatile', 'constexpr',
              'consteval', '&', 'try'}
STRING_PREFIXES = {'u8', 'u', 'U', 'L'}


class Token:
    __slots__ = ('text', 'line')

    def __init__(self, text, line):
        self.text = text
        self.line = line

    def __repr__(self):
        return f'{self.text}@{self.line}'


def is_identifier(text):
    return text[:1].isalpha() or text[:1] == '_'


def tokens_of(source):
    """The tokens of one C++ file: identifiers, numbers and punctuation, with
    every string or character literal as one `"` token and comments and
    preprocessor lines dropped."""
    out = []
    i, n, line = 0, len(source), 1
    at_line_start = True
    while i < n:
        c = source[i]
        if c == '\n':
            line += 1
            i += 1
            at_line_start = True
            continue
        if c in ' \t\r\f\v':
            i += 1
            continue
        if c == '\\' and i + 1 < n and source[i + 1] == '\n':
            i += 2
            line += 1
            continue
        if c == '#' and at_line_start:  # a directive, with its continuations
            while i < n and source[i] != '\n':
                if source.startswith('/*', i):
                    end = source.find('*/', i + 2)
                    end = n if end < 0 else end + 2
                    line += source.count('\n', i, end)
                    i = end
                    continue
                if source[i] == '\\' and i + 1 < n and source[i + 1] == '\n':
                    line += 1
                    i += 2
                    continue
                if source.startswith('//', i):
                    while i < n and source[i] != '\n':
                        i += 1
                    break
                i += 1
            continue
        at_line_start = False
        if source.startswith('//', i):
            while i < n and source[i] != '\n':
                i += 1
            continue
        if source.startswith('/*', i):
            end = source.find('*/', i + 2)
            end = n if end < 0 else end + 2
            line += source.count('\n', i, end)
            i = end
            continue
        if c.isalpha() or c == '_':
            j = i
            while j < n and (source[j].isalnum() or source[j] == '_'):
                j += 1
            word = source[i:j]
            raw = word.endswith('R') and word[:-1] in STRING_PREFIXES | {''}
            if j < n and source[j] == '"' and raw:
                # A raw string: R"delim( ... )delim", nothing inside escapes.
                open_paren = source.find('(', j + 1)
                delimiter = source[j + 1:open_paren]
                close = source.find(')' + delimiter + '"', open_paren + 1)
                end = n if close < 0 else close + len(delimiter) + 2
                out.append(Token('"', line))
                line += source.count('\n', i, end)
                i = end
                continue
            if j < n and source[j] in '"\'' and word in STRING_PREFIXES:
                i = j  # the literal itself follows
                continue
            out.append(Token(word, line))
            i = j
            continue
        if c.isdigit() or (c == '.' and i + 1 < n and source[i + 1].isdigit()):
            j = i + 1
            while j < n:
                if source[j] in 'eEpP' and j + 1 < n and source[j + 1] in '+-':
                    j += 2
                elif source[j].isalnum() or source[j] in "_.'":
                    j += 1
                else:
                    break
            out.append(Token(source[i:j], line))
            i = j
            continue
        if c in '"\'':
            j = i + 1
            while j < n and source[j] != c:
                if source[j] == '\\':
                    j += 1
                elif source[j] == '\n':
                    break  # unterminated: stop at the line's end
                j += 1
            out.append(Token('"', line))
            i = j + 1
            continue
        if source.startswith('::', i) or source.startswith('->', i):
            out.append(Token(source[i:i + 2], line))
            i += 2
            continue
        out.append(Token(c, line))
        i += 1
    return out, line


class Frame:
    """One open brace: what it opens and the tokens read at its level since
    the last declaration there ended."""

    def __init__(self, kind, name='', start_line=0):
        self.kind = kind  # top, namespace, class, enum, init, function, block
        self.name = name
        self.start_line = start_line
        self.head = []  # this level's tokens of the declaration being read
        self.parens = 0  # ( and [ open at this level


def depth0(head):
    """The tokens of a declaration outside (), [] and template <> (the
    outermost brackets themselves included)."""
    parens = angles = 0
    after_operator = False
    for k, t in enumerate(head):
        x = t.text
        if after_operator:
            if x == '(':
                after_operator = False
                yield k, t
            continue
        if x == 'operator':
            after_operator = True
            yield k, t
            continue
        if x in '([':
            if parens == 0 and angles == 0:
                yield k, t
            parens += 1
        elif x in ')]':
            parens = max(0, parens - 1)
            if parens == 0 and angles == 0:
                yield k, t
        elif parens == 0 and x == '<':
            angles += 1
        elif parens == 0 and x == '>' and angles:
            angles -= 1
        elif parens == 0 and angles == 0:
            yield k, t


def matching_open(head, k, close, open_):
    depth = 0
    while k >= 0:
        if head[k].text == close:
            depth += 1
        elif head[k].text == open_:
            depth -= 1
            if depth == 0:
                return k
        k -= 1
    return -1


def lambda_start(head):
    """The index of a lambda's `[` when `head` ends with a lambda's
    declarator ([...](...) qualifiers -> type), else -1."""
    k = len(head) - 1
    # A trailing return type: -> T, -> ns::T<...>, -> const T&
    j = k
    while j >= 0 and (is_identifier(head[j].text) or head[j].text in ('::', '<', '>', '*', '&',
                                                                      ',')):
        j -= 1
    if j >= 0 and head[j].text == '->':
        k = j - 1
    while k >= 0 and head[k].text in QUALIFIERS:
        k -= 1
    if k >= 0 and head[k].text == ')':
        k = matching_open(head, k, ')', '(') - 1
    if k < 0 or head[k].text != ']':
        return -1
    open_ = matching_open(head, k, ']', '[')
    if open_ < 0:
        return -1
    before = head[open_ - 1].text if open_ > 0 else ''
    subscripted = is_identifier(before) and before not in ('return', 'co_return', 'co_yield')
    if subscripted or before in (']', ')', '"'):
        return -1  # a subscript or an array's bound, not a capture list
    return open_


def function_name(head, frames):
    """A function's name as its declaration writes it (Api::handle), with
    the classes it is defined in (Session::receive)."""
    name = '?'
    for k, t in depth0(head):
        if t.text != '(' or k == 0:
            continue
        j = k - 1
        if head[j].text != 'operator' and any(h.text == 'operator' for h in head[max(0, j - 3):j]):
            while head[j].text != 'operator':  # operator==, operator(), operator[]
                j -= 1
        parts = [''.join(h.text for h in head[j:k])]
        while j >= 2 and head[j - 1].text == '::' and is_identifier(head[j - 2].text):
            parts.insert(0, head[j - 2].text)
            j -= 2
        if j >= 1 and head[j - 1].text == '~':
            parts[-1] = '~' + parts[-1]
        name = '::'.join(parts)
        break
    classes = [f.name for f in frames if f.kind == 'class' and f.name]
    return '::'.join(classes + [name])


def classify(frame, frames):
    """What a `{` read at `frame`'s level opens."""
    head = frame.head
    if frame.kind in ('function', 'block'):
        return 'block', ''
    lam = lambda_start(head)
    if lam >= 0:
        return 'lambda', lam
    if frame.kind in ('init', 'enum') or frame.parens > 0:
        prev = head[-1].text if head else ''
        if prev == ')':
            return 'lambda', None  # e.g. decltype(...){}: counted as one, harmlessly
        return 'init', ''
    top = [t.text for _, t in depth0(head)]
    if 'namespace' in top or (top[:1] == ['extern'] and top[1:] == ['"']):
        return 'namespace', ''
    for keyword in ('enum', 'class', 'struct', 'union'):
        if keyword in top:
            after = top[top.index(keyword) + 1:]
            if '(' not in after and '=' not in top[:top.index(keyword)]:
                names = [x for x in after
                         if is_identifier(x) and x not in ('class', 'struct', 'final')]
                kind = 'enum' if keyword == 'enum' else 'class'
                return kind, names[0] if names else ''
    if '=' in top and 'operator' not in top:
        return 'init', ''
    if '(' in top:
        prev = head[-1].text
        # A constructor's member initialized with braces, a_{x}, after `) :`.
        closes = [k for k, x in enumerate(top) if x == ')']
        in_init_list = closes and ':' in top[closes[0]:]
        if in_init_list and (is_identifier(prev) or prev == '>'):
            return 'init', ''
        return 'function', ''
    return 'init', ''


def measure(path, text):
    """(functions [(lines, line, name)], problem or None) of one file."""
    tokens, _ = tokens_of(text)
    frames = [Frame('top')]
    functions = []
    for t in tokens:
        frame = frames[-1]
        x = t.text
        if x == '{':
            kind, extra = classify(frame, frames)
            if kind == 'block':
                frames.append(Frame('block'))
            elif kind in ('function', 'lambda'):
                if kind == 'lambda':
                    start = frame.head[extra].line if extra is not None else t.line
                    name = 'lambda'
                else:
                    start = frame.head[0].line if frame.head else t.line
                    name = function_name(frame.head, frames)
                frames.append(Frame('function', name, start))
            else:
                frames.append(Frame(kind, extra, t.line))
            continue
        if x == '}':
            if len(frames) == 1:
                return functions, f'{path}:{t.line}: a closing brace that closes nothing'
            done = frames.pop()
            parent = frames[-1]
            if done.kind == 'function':
                functions.append((t.line - done.start_line + 1, done.start_line, done.name))
            scope_level = parent.kind in ('top', 'namespace', 'class') and parent.parens == 0
            if scope_level and done.kind in ('function', 'namespace') and done.name != 'lambda':
                parent.head = []
            else:
                parent.head.append(Token('}', t.line))
            continue
        if frame.kind in ('function', 'block'):
            continue
        if x in '([':
            frame.parens += 1
        elif x in ')]':
            frame.parens = max(0, frame.parens - 1)
        if x == ';' and frame.parens == 0:
            frame.head = []
            continue
        if (x == ':' and frame.kind == 'class' and len(frame.head) == 1
                and frame.head[0].text in ('public', 'private', 'protected')):
            frame.head = []
            continue
        frame.head.append(t)
    if len(frames) != 1:
        return functions, (f'{path}:{frames[-1].start_line}: the braces do not balance (this one '
                           f'is never closed; braces split across #if branches?)')
    return functions, None


def sources(dirs):
    for d in dirs:
        if os.path.isfile(d):
            yield d
            continue
        for root, subdirs, files in os.walk(d):
            subdirs.sort()
            for f in sorted(files):
                if f.endswith(CXX_SUFFIXES):
                    yield os.path.join(root, f)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--max-file-lines', type=int, default=400)
    parser.add_argument('--max-function-lines', type=int, default=60)
    parser.add_argument('--root', default='.', help='paths are printed relative to it')
    parser.add_argument('dirs', nargs='+')
    args = parser.parse_args()

    over = unreadable = 0
    longest_function = (0, '', 0, '')
    longest_file = (0, '')
    files = functions_seen = 0
    for path in sources(args.dirs):
        shown = os.path.relpath(path, args.root)
        with open(path, encoding='utf-8') as f:
            text = f.read()
        files += 1
        lines = text.count('\n') + (0 if text.endswith('\n') or not text else 1)
        if lines > longest_file[0]:
            longest_file = (lines, shown)
        if lines > args.max_file_lines:
            print(f'{shown}:1: the file has {lines} lines (at most {args.max_file_lines})')
            over += 1
        functions, problem = measure(shown, text)
        if problem:
            print(problem + ': cannot measure its functions')
            unreadable += 1
        for length, line, name in functions:
            functions_seen += 1
            if length > longest_function[0]:
                longest_function = (length, shown, line, name)
            if length > args.max_function_lines:
                print(f'{shown}:{line}: function \'{name}\' has {length} lines '
                      f'(at most {args.max_function_lines})')
                over += 1
    length, shown, line, name = longest_function
    longest = f'{shown}:{line} \'{name}\' ({length} lines' if length else 'none (0 lines'
    print(f'{files} files, {functions_seen} functions; longest function: {longest}, at most '
          f'{args.max_function_lines}); longest file: {longest_file[1]} ({longest_file[0]} '
          f'lines, at most {args.max_file_lines})')
    if files == 0:
        print('no C++ files found in ' + ' '.join(args.dirs))
        return 2
    return 2 if unreadable else (1 if over else 0)


if __name__ == '__main__':
    sys.exit(main())
