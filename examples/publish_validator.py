"""A publish validator for material sets, Pyblish-style: a pipeline's publish step runs it on each
instance (a material set a user is about to publish) and it fails the publish on the findings of
`matforge validate` at or above a severity, logging every finding.

In Pyblish (pyblish.api installed), it is an InstancePlugin at ValidatorOrder for the families
"material" and "textureSet": register it with pyblish.api.register_plugin(ValidateMaterialSet).
Without Pyblish it runs as well, on any object with `data` (a dict) and `name`:

    python3 examples/publish_validator.py FOLDER [--fail-on warning] [--rules rules.json]

exits 0 when the set passes, 1 when it fails (each finding on stderr), like `matforge validate`.

The instance's data it reads: "materialFolder" (the set's folder or .zip, required),
"matforgeRules" (a rules file or object, docs/rules.md), "matforgePreset" (default "gltf");
it writes "matforgeFindings" (the findings, typed) for later plugins (an extractor that ingests).
"""

from __future__ import annotations

import argparse
import json
import logging
import sys
from typing import Any, Dict, List

import matforge

try:  # Pyblish is optional: the plugin is the same class either way.
    import pyblish.api as _pyblish

    _Plugin: Any = _pyblish.InstancePlugin
    _VALIDATOR_ORDER = _pyblish.ValidatorOrder
except ImportError:
    _Plugin = object
    _VALIDATOR_ORDER = 1  # pyblish.api.ValidatorOrder


class MaterialSetInvalid(Exception):
    """The set has findings at or above the plugin's `fail_on`, or could not be read."""

    def __init__(self, message: str, findings: List[matforge.Finding]) -> None:
        super().__init__(message)
        self.findings = findings


class ValidateMaterialSet(_Plugin):  # type: ignore[misc, valid-type]
    """Fails the publish of a material set with findings at or above `fail_on`."""

    order = _VALIDATOR_ORDER
    label = "Material set (matforge validate)"
    families = ["material", "textureSet"]
    hosts = ["*"]
    fail_on = "error"  # "error", "warning" or "info"

    def __init__(self) -> None:
        if _Plugin is not object:
            super().__init__()
        self.log = getattr(self, "log", None) or logging.getLogger("matforge.publish")

    def process(self, instance: Any) -> None:
        data: Dict[str, Any] = instance.data
        folder = data["materialFolder"]
        try:
            result = matforge.validate(folder, rules=data.get("matforgeRules"),
                                       preset=data.get("matforgePreset", "gltf"))
        except matforge.Error as e:  # an unreadable folder, bad rules: the publish cannot pass
            raise MaterialSetInvalid(f"{instance.name}: {e.code}: {e}", []) from e
        data["matforgeFindings"] = list(result.findings)
        threshold = matforge.Severity(self.fail_on)
        failing = [f for f in result.findings if f.severity >= threshold]
        for f in result.findings:
            level = logging.ERROR if f in failing else logging.WARNING if f.severity != "info" else logging.INFO
            self.log.log(level, "%s", f)
        for failure in result.failures:
            self.log.error("%s: %s", failure.code, failure.message)
        if failing or result.failures:
            codes = sorted({f.code for f in failing} | {f.code for f in result.failures})
            raise MaterialSetInvalid(
                f"{instance.name}: {len(failing)} finding(s) at or above {self.fail_on}, "
                f"{len(result.failures)} input(s) not read ({', '.join(codes)})", failing)


class Instance:
    """The least of pyblish.api.Instance the plugin needs: a name and its data."""

    def __init__(self, name: str, **data: Any) -> None:
        self.name = name
        self.data: Dict[str, Any] = dict(data)


def main(argv: List[str]) -> int:
    parser = argparse.ArgumentParser(description="Validate a material set as a publish step would.")
    parser.add_argument("folder", help="the material set's folder or .zip")
    parser.add_argument("--fail-on", default="error", choices=["error", "warning", "info"])
    parser.add_argument("--rules", help="a rules file (docs/rules.md)")
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.INFO, format="%(levelname)s %(message)s")
    plugin = ValidateMaterialSet()
    plugin.fail_on = args.fail_on
    instance = Instance(args.folder, materialFolder=args.folder, matforgeRules=args.rules)
    try:
        plugin.process(instance)
    except MaterialSetInvalid as e:
        print(f"publish refused: {e}", file=sys.stderr)
        return 1
    print(json.dumps({"passed": True, "findings": len(instance.data["matforgeFindings"])}))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
