#!/usr/bin/env python3
"""Generate lamina's man pages from the commands' --help texts.

lamina(1) comes from `lamina --help` and man/lamina.1.in; lamina-CMD(1) from
`lamina CMD --help` and man/lamina-CMD.1.in (optional). What --help says is
generated -- NAME, SYNOPSIS, the help's prose, every option with its
argument and text, EXIT STATUS -- so a page cannot list an option that
--help does not, or miss one it does. The .in files add what a help screen
has no room for: more DESCRIPTION, EXAMPLES, other sections, and the text
of options that --help only names in its usage line (`.\\"@option --json`).
man/common.in holds ENVIRONMENT and FILES for every page; an entry marked
`.\\"@env NAME` is kept only when a built binary contains NAME (so
LAMINA_THREADS appears once lamina reads it).

How a help text reads (lua/cli/*.c):
  usage: lamina CMD ...            the synopsis; continuation lines indented
  prose at column 0                description (a last sentence ending in ':'
                                   just before a table heads that table)
  "  -x, --long ARG  text"         an option table entry; deeper indented
                                   lines continue its text
"""
import argparse
import datetime
import os
import re
import subprocess
import sys
import textwrap

OPT_TOKEN = re.compile(r'(?<![\w-])(--?[A-Za-z][\w-]*)')
# a table entry: "-x, --long ARG  text", "--long ARG text", "-x  text"
ENTRY = re.compile(r'^\s+(?:(-[A-Za-z0-9]),\s+)?(--?[A-Za-z0-9][\w-]*)'
                   r'(?:([ =])([A-Z][A-Z0-9_.,|=:-]*))?(?:\s+(\S.*))?$')


def run_help(lamina, args):
    p = subprocess.run([lamina] + args, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                       universal_newlines=True)
    if p.returncode != 0:
        sys.exit('genman: %s %s exited %d: %s' % (lamina, ' '.join(args), p.returncode, p.stderr))
    return p.stdout


# ---- parsing the help texts --------------------------------------------------

class Entry:
    def __init__(self, names, arg, text):
        self.names = names        # ["-m", "--machine"] or ["--json"]
        self.arg = arg            # "MACHINE" or None
        self.text = text          # from the help, or None


def synopsis_options(lines):
    """(option, argument or None) in order of the usage lines."""
    out = []
    toks = ' '.join(lines).split()
    for i, t in enumerate(toks):
        m = re.match(r'^\[*(--?[A-Za-z][\w-]*)(=(\S+))?(\]*)', t)
        if not m or t.startswith('-') and len(t) > 1 and t[1].isdigit():
            continue
        opt, arg = m.group(1), m.group(3)
        closed = bool(m.group(4)) or t.endswith(']')
        if arg is None and not closed and i + 1 < len(toks):
            nxt = toks[i + 1]
            if not nxt.startswith(('[', '-', '|')) and nxt != '...':
                arg = nxt.rstrip(']')
        if arg in ('...', ''):
            arg = None
        out.append((opt, arg))
    return out


def parse_command_help(text):
    """Synopsis lines, description prose, option groups [(header, [Entry])]."""
    lines = text.rstrip('\n').split('\n')
    syn, i = [], 0
    while i < len(lines) and (i == 0 or re.match(r'^ {4,}\S', lines[i]) and
                              not lines[i].lstrip().startswith('-')):
        # continuation lines keep their alignment under the text after "usage: "
        line = lines[i]
        syn.append(re.sub(r'^usage: ', '', line) if i == 0 else line[7:] if line.startswith(' ' * 7) else line.strip())
        i += 1
    blocks = []     # ("prose", [lines]) or ("table", [Entry])
    for line in lines[i:]:
        if not line.strip():
            continue
        if not line[0].isspace():
            if blocks and blocks[-1][0] == 'prose':
                blocks[-1][1].append(line)
            else:
                blocks.append(('prose', [line]))
            continue
        m = ENTRY.match(line) if line.lstrip().startswith('-') else None
        if m:
            names = [n for n in (m.group(1), m.group(2)) if n]
            arg = m.group(4)
            txt = m.group(5) or ''
            e = Entry(names, arg, txt)
            if blocks and blocks[-1][0] == 'table':
                blocks[-1][1].append(e)
            else:
                blocks.append(('table', [e]))
        elif blocks and blocks[-1][0] == 'table':
            e = blocks[-1][1][-1]
            e.text = (e.text + ' ' + line.strip()).strip()
        else:
            if blocks and blocks[-1][0] == 'prose':
                blocks[-1][1].append(line.strip())
            else:
                blocks.append(('prose', [line.strip()]))
    description, groups = [], []
    for k, (kind, body) in enumerate(blocks):
        if kind == 'prose':
            text = ' '.join(body)
            nxt_table = k + 1 < len(blocks) and blocks[k + 1][0] == 'table'
            first_table = not any(b[0] == 'table' for b in blocks[:k])
            head = ''
            if nxt_table and text.endswith(':'):
                # the last sentence heads the table
                parts = re.split(r'(?<=[.;])\s+(?=[A-Z])', text)
                head = parts[-1]
                text = ' '.join(parts[:-1])
            if first_table:
                if text:
                    description.append(text)
                if head:
                    groups.append([head, []])
            else:
                groups.append([(text + ' ' + head).strip(), []])
        else:
            if not groups or groups[-1][1]:
                groups.append(['', []])
            groups[-1][1].extend(body)
    return syn, description, groups


def parse_main_help(text):
    lines = text.rstrip('\n').split('\n')
    title = re.sub(r'^lamina \S+ - ', '', lines[0])
    cmds, opts, prose, cur = [], [], [], None
    i = 1
    while i < len(lines) and lines[i].strip() != 'usage:':
        i += 1
    i += 1
    while i < len(lines) and lines[i].strip():
        line = lines[i]
        m = re.match(r'^  (lamina\s.*?)(?:\s{2,}(\S.*))?$', line)
        if m:
            syn, desc = m.group(1).strip(), m.group(2) or ''
            cm = re.match(r'^lamina ([a-z][a-z0-9-]*)\b(.*)$', syn)
            cur = [cm.group(1), syn, desc] if cm else [None, syn, desc]
            (cmds if cm else opts).append(cur)
        elif cur is not None:
            cur[2] = (cur[2] + ' ' + line.strip()).strip()
        i += 1
    prose = ' '.join(l.strip() for l in lines[i:] if l.strip())
    return title, cmds, opts, prose


def exit_codes(prose):
    m = re.search(r'Exit codes: (.*?\.)(?:\s|$)', prose)
    if not m:
        return []
    return re.findall(r'(\d+) ([^,]+?)(?:,|\.$)', m.group(1))


# ---- the hand-written parts ------------------------------------------------

def read_in(path):
    """Sections {NAME: roff} in order, and option texts {option: roff}."""
    sections, options = [], {}
    if not os.path.exists(path):
        return sections, options
    cur = None
    for line in open(path, encoding='utf-8').read().split('\n'):
        m = re.match(r'^\.SH\s+"?([^"]*)"?\s*$', line)
        o = re.match(r'^\.\\"@option\s+(\S+)\s*$', line)
        if m:
            cur = [m.group(1), []]
            sections.append(cur)
        elif o:
            cur = [None, []]
            options[o.group(1)] = cur[1]
        elif cur is not None:
            cur[1].append(line)
    secs = [(name, '\n'.join(body).strip('\n')) for name, body in sections]
    return secs, {k: '\n'.join(v).strip('\n') for k, v in options.items()}


def common_sections(path, binaries):
    """ENVIRONMENT, FILES, ...: entries marked .\\"@env NAME kept when NAME is in a binary."""
    blob = b''
    for b in binaries:
        if b and os.path.exists(b):
            blob += open(b, 'rb').read()
    out, cur, keep = [], None, True
    for line in open(path, encoding='utf-8').read().split('\n'):
        m = re.match(r'^\.SH\s+"?([^"]*)"?\s*$', line)
        e = re.match(r'^\.\\"@env\s+(\S+)\s*$', line)
        if m:
            cur = [m.group(1), []]
            out.append(cur)
            keep = True
        elif e:
            keep = e.group(1).encode() in blob
        elif line.startswith('.\\"'):
            continue
        elif cur is not None and keep:
            cur[1].append(line)
    return [(n, '\n'.join(b).strip('\n')) for n, b in out]


# ---- roff ------------------------------------------------------------------

def esc(s):
    """Text for roff: backslashes, hyphens that start options, quotes at line start."""
    s = s.replace('\\', '\\e')
    s = re.sub(r'(?<![\w])-', r'\\-', s)
    s = s.replace("'", "\\(aq").replace('`', "\\(ga")
    return s


def para(s):
    """Prose as filled text: a sentence starts a line, lines at most 79 bytes."""
    s = esc(s.strip())
    out = []
    for sent in re.split(r'(?<=[.;:?!])\s+(?=[A-Z\\(\'"])', s):
        out += textwrap.wrap(sent, 79, break_long_words=False, break_on_hyphens=False)
    return '\n'.join(l if not l.startswith(('.', "'")) else '\\&' + l for l in out)


def sentence(s):
    """A help's terse text as a sentence: capital first letter, final stop."""
    s = s.strip()
    if s.startswith('-'):
        return 'Short for ' + s + '.'
    if s and s[0].islower() and not re.match(r'^[a-z_]+[.=(]', s):
        s = s[0].upper() + s[1:]
    return s if not s or s[-1] in '.:!?' else s + '.'


def opt_head(e):
    names = ', '.join('\\fB%s\\fR' % esc(n) for n in e.names)
    if e.arg:
        names += ' \\fI%s\\fR' % esc(e.arg)
    return names


def see_also(self_page, cmds):
    pages = ['lamina'] + ['lamina-' + c for c in cmds]
    refs = ['.BR %s (1)' % esc(p) for p in pages if p != self_page] + ['.BR lua5.4 (1)']
    return ',\n'.join(refs)


def page(name, version, date, title, synopsis_roff, description, options_roff, extra_secs, common, cmds, exits):
    out = ['.\\" Generated by man/genman.py from `%s --help` and man/%s.1.in: edit those.'
           % (name.replace('-', ' '), name),
           '.TH %s 1 %s "lamina %s" "lamina manual"' % (esc(name.upper()), date, version),
           '.SH NAME', '%s \\- %s' % (esc(name), esc(title)),
           '.SH SYNOPSIS', synopsis_roff, '.SH DESCRIPTION', description]
    extra = dict(extra_secs)
    if options_roff:
        out += ['.SH OPTIONS', options_roff]
    for sname, body in extra_secs:
        if sname not in ('DESCRIPTION', 'EXAMPLES', 'EXIT STATUS', 'SEE ALSO'):
            out += ['.SH ' + sname, body]
    if 'EXIT STATUS' in extra:
        out += ['.SH "EXIT STATUS"', extra['EXIT STATUS']]
    elif exits:
        out += ['.SH "EXIT STATUS"']
        for code, what in exits:
            out += ['.TP', '.B %s' % code, para(what[0].upper() + what[1:] + '.')]
    for sname, body in common:
        out += ['.SH ' + sname, body]
    if 'EXAMPLES' in extra:
        out += ['.SH EXAMPLES', extra['EXAMPLES']]
    out += ['.SH "SEE ALSO"', see_also(name, cmds)]
    return '\n'.join(x for x in out if x is not None) + '\n'


def synopsis_block(lines):
    out = ['.nf']
    for l in lines:
        e = esc(l.rstrip())
        e = re.sub(r'^(\s*)lamina (\S+)', lambda m: m.group(1) + '\\fBlamina %s\\fR' % m.group(2), e)
        out.append('\\&' + e)
    out.append('.fi')
    return '\n'.join(out)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--lamina', required=True)
    ap.add_argument('--in', dest='indir', required=True)
    ap.add_argument('--out', required=True)
    ap.add_argument('--version', required=True)
    ap.add_argument('--binaries', default='', help='binaries, separated by spaces (relative paths)')
    ap.add_argument('--binary', action='append', default=[], help='one binary (a path that may hold spaces)')
    ap.add_argument('--expect', default=None, help='the commands the Makefile installs pages for')
    ap.add_argument('--completion-in', default=None, help='bash completion template (completion/lamina.bash.in)')
    ap.add_argument('--completion-out', default=None)
    a = ap.parse_args()

    if os.environ.get('SOURCE_DATE_EPOCH'):
        when = datetime.datetime.utcfromtimestamp(int(os.environ['SOURCE_DATE_EPOCH']))
    else:
        when = datetime.datetime.utcfromtimestamp(os.path.getmtime(os.path.join(a.indir, 'common.in')))
        try:
            g = subprocess.run(['git', '-C', a.indir, 'log', '-1', '--format=%ct'], stdout=subprocess.PIPE,
                               stderr=subprocess.DEVNULL, universal_newlines=True)
            if g.returncode == 0 and g.stdout.strip():
                when = datetime.datetime.utcfromtimestamp(int(g.stdout.strip()))
        except OSError:
            pass
    date = when.strftime('%Y-%m-%d')

    title, cmds, topopts, prose = parse_main_help(run_help(a.lamina, ['--help']))
    names = [c[0] for c in cmds]
    if a.expect is not None and sorted(a.expect.split()) != sorted(names):
        sys.exit('genman: `lamina --help` lists the commands %s, the Makefile (the command table of lua/cli/main.c) %s'
                 % (' '.join(names), a.expect))
    exits = exit_codes(prose)
    common = common_sections(os.path.join(a.indir, 'common.in'), a.binaries.split() + a.binary)
    os.makedirs(a.out, exist_ok=True)

    helps = {c: parse_command_help(run_help(a.lamina, [c, '--help'])) for c in names}
    # short/long pairs and arguments from every help: one option table serves all commands
    pairs, args_seen, texts_seen, syn_seen = {}, {}, {}, {}
    for c, (syn, desc, groups) in helps.items():
        for _, entries in groups:
            for e in entries:
                if len(e.names) == 2:
                    pairs[e.names[0]] = e.names[1]
                for n in e.names:
                    if e.arg:
                        args_seen.setdefault(n, e.arg)
                    if e.text:
                        texts_seen.setdefault(n, e.text)
        for o, arg in synopsis_options(syn):
            if arg:
                args_seen.setdefault(o, arg)
                if '|' in arg:
                    syn_seen.setdefault(o, arg)
    for c, (syn, desc, groups) in helps.items():
        for p in desc:
            for s, l in re.findall(r'(?<![\w-])(-[A-Za-z])/(--[\w-]+)', p):
                pairs.setdefault(s, l)
    stale = []
    cmd_entries = {}

    def render_entries(groups, extra_opts, tag):
        out = []
        for head, entries in groups:
            if head:
                out += ['.PP', para(head)]
            for e in entries:
                text = e.text
                if not text:
                    hand = next((extra_opts[n] for n in e.names if n in extra_opts), None)
                    if hand is None and any(n in texts_seen for n in e.names):
                        # the same option of another command (one option table serves all)
                        hand = para(sentence(next(texts_seen[n] for n in e.names if n in texts_seen)))
                    if hand is None:
                        stale.append('`%s --help` names %s without a text, and man/%s.1.in has none'
                                     % (tag.replace('-', ' '), e.names[-1], tag))
                    text_roff = hand if hand is not None else 'See\n.BR DESCRIPTION .'
                else:
                    text_roff = para(sentence(text))
                    hand = next((extra_opts[n] for n in e.names if n in extra_opts), None)
                    if hand:
                        text_roff += '\n' + hand
                out += ['.TP', opt_head(e), text_roff]
        known = {n for _, entries in groups for e in entries for n in e.names}
        for o in extra_opts:
            if o not in known:
                stale.append('man/%s.1.in describes %s, which `%s --help` does not list' % (tag, o, tag.replace('-', ' ')))
        return '\n'.join(out)

    # lamina(1)
    secs, extra_opts = read_in(os.path.join(a.indir, 'lamina.1.in'))
    syn = ['lamina ' + re.sub(r'^lamina ', '', s) for _, s, _ in cmds + topopts]
    cmd_roff = []
    for c, s, d in cmds:
        cmd_roff += ['.TP', '\\fB%s\\fR' % esc(s), para(d[0].upper() + d[1:] + '.' if d else ''),
                     'See\n.BR %s (1).' % esc('lamina-' + c)]
    top_entries = []
    for _, s, d in topopts:
        opts = [o for o, _ in synopsis_options([s])]
        for o, arg in synopsis_options([s]):
            if any(o in e.names for e in top_entries):
                continue
            top_entries.append(Entry([o], arg, d if len(set(opts)) == 1 else None))
    hand_desc = dict(secs).get('DESCRIPTION', '')
    other_prose = re.sub(r'\s*Exit codes: .*$', '', prose)
    description = '\n'.join(x for x in [hand_desc, '.PP', para(other_prose)] if x)
    options_roff = render_entries([['', top_entries]], extra_opts, 'lamina')
    body = page('lamina', a.version, date, title, synopsis_block(syn), description, options_roff,
                [('COMMANDS', '\n'.join(cmd_roff))] + [s for s in secs if s[0] != 'DESCRIPTION'],
                common, names, exits)
    open(os.path.join(a.out, 'lamina.1'), 'w').write(body)

    for c, s, d in cmds:
        syn, desc, groups = helps[c]
        secs, extra_opts = read_in(os.path.join(a.indir, 'lamina-%s.1.in' % c))
        # options named only in the usage lines join the first group
        listed = {n for _, entries in groups for e in entries for n in e.names}
        first = None
        for o, arg in synopsis_options(syn):
            if o in listed:
                continue
            long_ = pairs.get(o)
            short = next((k for k, v in pairs.items() if v == o), None)
            names_ = [o, long_] if long_ else [short, o] if short else [o]
            e = Entry(names_, arg if arg else next((args_seen[n] for n in names_ if n in args_seen), None), None)
            if first is None:
                if not groups or groups[0][0]:
                    groups.insert(0, ['', []])
                first = groups[0][1]
            first.append(e)
            listed.update(names_)
        for _, entries in groups:
            for e in entries:
                # the usage line's name for the value (WIDTH, floor|middle|ceiling)
                # says more than the table's generic one (X, VALUE)
                own = {o: v for o, v in synopsis_options(syn) if v}
                better = next((own[n] for n in e.names if n in own), None) or \
                    next((syn_seen[n] for n in e.names if n in syn_seen), None)
                if better and (not e.arg or e.arg in ('X', 'N', 'VALUE')):
                    e.arg = better
        cmd_entries[c] = ([e for _, entries in groups for e in entries], positional(syn))
        hand_desc = dict(secs).get('DESCRIPTION', '')
        description = '\n.PP\n'.join([para(p) for p in desc] + ([hand_desc] if hand_desc else [])) or para(d)
        options_roff = render_entries(groups, extra_opts, 'lamina-' + c)
        body = page('lamina-' + c, a.version, date, d, synopsis_block(syn), description, options_roff,
                    secs, common, names, exits)
        open(os.path.join(a.out, 'lamina-%s.1' % c), 'w').write(body)
    for s in stale:
        print('genman: warning: ' + s, file=sys.stderr)
    if a.completion_in:
        write_completion(a.completion_in, a.completion_out, names, top_entries, cmd_entries)


def bash_word(s):
    return "'" + s.replace("'", "'\\''") + "'"


def write_completion(template, out, names, top_entries, cmd_entries):
    """The bash completion: template with the commands' options filled in."""
    data = ['_lamina_commands=%s' % bash_word(' '.join(names)),
            '_lamina_top_opts=%s' % bash_word(' '.join(n for e in top_entries for n in e.names)),
            'declare -gA _lamina_opts=(' + ' '.join(
                '[%s]=%s' % (c, bash_word(' '.join(n for e in es for n in e.names)))
                for c, (es, _) in cmd_entries.items()) + ')',
            'declare -gA _lamina_positional=(' + ' '.join(
                '[%s]=%s' % (c, bash_word(p or '')) for c, (_, p) in cmd_entries.items()) + ')']
    args = ['[%s]=%s' % (bash_word('- ' + n), bash_word(e.arg)) for e in top_entries if e.arg for n in e.names]
    for c, (es, _) in cmd_entries.items():
        args += ['[%s]=%s' % (bash_word(c + ' ' + n), bash_word(e.arg)) for e in es if e.arg for n in e.names]
    data.append('declare -gA _lamina_optargs=(' + ' '.join(args) + ')')
    text = open(template, encoding='utf-8').read()
    if '@DATA@' not in text:
        sys.exit('genman: %s has no @DATA@ line' % template)
    open(out, 'w').write(text.replace('@DATA@', '\n'.join(data)))


def positional(syn):
    """The first argument of the usage line that is not an option or an option's value (MODEL)."""
    toks = ' '.join(syn).split()
    skip = set()
    for i, t in enumerate(toks):
        m = re.match(r'^\[*(--?[A-Za-z][\w-]*)(\]*)$', t)
        if m and not m.group(2) and i + 1 < len(toks) and not toks[i + 1].startswith(('[', '-', '|')):
            skip.add(i + 1)
    for i, t in enumerate(toks[2:], 2):
        if i not in skip and re.match(r'^[A-Z][\w.]*$', t):
            return t
    return None


if __name__ == '__main__':
    main()
