"""`inspect`: measure structure files without building anything."""
from __future__ import annotations

import json
import sys

from ..exits import EXIT_OK, UsageError
from .. import files
from ..structure.from_files import has_structure, measure_all


def command_inspect(args) -> int:
    """The measurements as text (stdout), and with --json as JSON ('-': stdout, text to stderr)."""
    from .. import structure
    from ..structure import inspect_text
    if not has_structure(args):
        raise UsageError("inspect: give --fibril FILE, --domain FILE and/or --full-length FILE")
    to_stdout = args.json == files.STDOUT  # the JSON on stdout, the text on stderr
    path = (files.check_writable("--json", args.json, (".json",))
            if args.json and not to_stdout else None)
    fib, doms, seg = measure_all(args, inspect=True)
    dom = doms[0] if doms else None
    values = structure.model_values(fib, dom, more_domains=doms[1:])
    if args.json:
        import gemmi
        from ..structure.mapping import linker_source
        sources = ({"linker": linker_source(fib, dom, explicit=False)} if fib or dom else {})
        doc = {"fibril": fib and fib.to_dict(), "domain": dom and dom.to_dict(),
               "model_values": values, "sources": sources, "gemmi_version": gemmi.__version__}
        if seg is not None:
            doc.update(full_length=seg.to_dict(), domains=seg.domains, linkers=seg.linkers)
        if len(doms) > 1:
            doc["domains_measured"] = [d.to_dict() for d in doms]
        if path:
            files.write_json(path, doc)
    print(inspect_text.text(fib, dom, values, segmentation=seg, more_domains=doms[1:]),
          file=sys.stderr if to_stdout else sys.stdout)
    if to_stdout:
        print(json.dumps(doc, indent=2))
    return EXIT_OK
