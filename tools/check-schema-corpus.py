#!/usr/bin/python3
"""Run an independent JSON Schema validator (Debian python3-jsonschema, Draft 2020-12) over the
scenario corpus: every broken scenario whose error JSON Schema can express must be rejected by
config/schema/scenario.schema.json alone (what an editor flags as it is typed), and every shipped
valid scenario must be accepted. The broken files the schema cannot judge are listed below with
why; a listed file that the schema starts rejecting is an error too (drop it from the list).

usage: check-schema-corpus.py [REPO_ROOT]      exit 0 ok, 1 mismatch, 77 jsonschema missing
"""
import glob
import json
import os
import sys

try:
    from jsonschema import Draft202012Validator
except ImportError:
    print("check-schema-corpus: python3-jsonschema is not installed (apt-get install python3-jsonschema)")
    sys.exit(77)

NOT_JSON = "not JSON: a schema validates a parsed document, the parser rejects this file"
INCLUDE = "about the included file, which a schema applied to one file never sees"
REFERENCE = ("a reference to a key defined elsewhere in the (merged) document; JSON Schema "
             "2020-12 has no cross-reference check ($data is not part of it)")
NOT_EXPRESSIBLE = {
    "bad-json.json": NOT_JSON,
    "empty.json": NOT_JSON,
    "trailing-comma.json": NOT_JSON,
    "include-cycle-a.json": INCLUDE,
    "include-cycle-b.json": INCLUDE,
    "include-device.json": INCLUDE,
    "missing-include.json": INCLUDE,
    "bad-clr-file.json": "the error is inside the referenced .clr file, not in the JSON",
    "unknown-store.json": REFERENCE,
    "unknown-transfer.json": REFERENCE,
    "unknown-visibility-layer.json": REFERENCE,
    "duplicate-layer-id.json": ("uniqueness of one property across array items (uniqueItems "
                                "compares whole items)"),
    "unsorted-stops.json": "order between the values of different array items",
    "offset-without-clock.json": ("time offsets need a clock that may come from an include; "
                                  "only the merged document can tell"),
}


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.getcwd()
    with open(os.path.join(root, "config/schema/scenario.schema.json")) as f:
        schema = json.load(f)
    Draft202012Validator.check_schema(schema)
    validator = Draft202012Validator(schema)
    failures = []
    rejected = []
    broken = sorted(glob.glob(os.path.join(root, "scenarios/broken/*.json")))
    for path in broken:
        name = os.path.basename(path)
        try:
            with open(path) as f:
                doc = json.load(f)
            errors = list(validator.iter_errors(doc))
        except ValueError:
            errors = None  # not JSON
        if name in NOT_EXPRESSIBLE:
            if errors:
                failures.append(f"{name}: listed as not expressible but the schema rejects it "
                                f"({errors[0].message[:100]}); drop it from NOT_EXPRESSIBLE")
            continue
        if errors is None:
            failures.append(f"{name}: not JSON but not listed as such")
        elif not errors:
            failures.append(f"{name}: the schema accepts this broken scenario")
        else:
            rejected.append(name)
            print(f"rejected {name}: {errors[0].json_path}: {errors[0].message[:120]}")
    for name in NOT_EXPRESSIBLE:
        if not os.path.exists(os.path.join(root, "scenarios/broken", name)):
            failures.append(f"{name}: listed but no such file in scenarios/broken")
        else:
            print(f"not expressible {name}: {NOT_EXPRESSIBLE[name]}")
    valid = sorted(glob.glob(os.path.join(root, "scenarios/demo/*.json")) +
                   glob.glob(os.path.join(root, "scenarios/mappings/*.json")))
    for path in valid:
        with open(path) as f:
            doc = json.load(f)
        errors = list(validator.iter_errors(doc))
        if errors:
            failures.append(f"{os.path.relpath(path, root)}: valid scenario rejected: "
                            f"{errors[0].json_path}: {errors[0].message[:120]}")
    print(f"{len(rejected)} of {len(broken)} broken scenarios rejected by the schema alone, "
          f"{len(NOT_EXPRESSIBLE)} not expressible; {len(valid)} valid scenarios accepted")
    for f in failures:
        print("FAIL " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
