#!/usr/bin/env python3
"""Checks the Kubernetes manifests in deploy/k8s without a cluster.

1. Schema: every document against the published Kubernetes JSON schemas, strictly (unknown
   fields are errors), for the oldest and the newest version the `kubernetes-validate` package
   ships (`pip install kubernetes-validate`; skipped with a message when it is absent).
2. What the schemas cannot say: the render Job is an Indexed Job whose SHARDS equals its
   completions and whose command takes the shard from JOB_COMPLETION_INDEX (+1: shards count
   from 1); it reads the cache the simulate Job writes; every pod mounts the claim that
   volume.yaml defines; both Jobs never restart a finished pod in place.

Exit status 0 when every check passed, 1 otherwise. Needs PyYAML.
"""

import pathlib
import re
import sys

import yaml

K8S = pathlib.Path(__file__).resolve().parent / "k8s"


def load():
    docs = {}
    for path in sorted(K8S.glob("*.yaml")):
        with open(path, encoding="utf-8") as f:
            items = [d for d in yaml.safe_load_all(f) if d is not None]
        docs[path.name] = items
    return docs


def schema_problems(docs):
    try:
        import kubernetes_validate
    except ImportError:
        print("skipped: schema check (pip install kubernetes-validate to run it)")
        return []
    versions = sorted(
        {"1.25.0", kubernetes_validate.latest_version()},
        key=lambda v: tuple(int(x) for x in v.split(".")),
    )
    problems = []
    for name, items in docs.items():
        for doc in items:
            for version in versions:
                try:
                    kubernetes_validate.validate(doc, version, strict=True)
                except kubernetes_validate.ValidationError as e:
                    path = ".".join(str(p) for p in e.path)
                    problems.append(f"{name}: Kubernetes {version}: {path}: {e.message}")
                except Exception as e:  # schema missing for a version, and the like
                    problems.append(f"{name}: Kubernetes {version}: {e}")
    print(f"schema check: {sum(len(v) for v in docs.values())} documents against Kubernetes {', '.join(versions)}")
    return problems


def one(docs, name, kind):
    items = [d for d in docs.get(name, []) if d.get("kind") == kind]
    if len(items) != 1:
        raise SystemExit(f"{name}: expected one {kind}, found {len(items)}")
    return items[0]


def flag_value(command, flag):
    m = re.search(re.escape(flag) + r"[= ]+(\S+)", command)
    return m.group(1) if m else None


def rule_problems(docs):
    problems = []
    claim = one(docs, "volume.yaml", "PersistentVolumeClaim")
    claim_name = claim["metadata"]["name"]
    if "ReadWriteMany" not in claim["spec"].get("accessModes", []):
        problems.append("volume.yaml: the claim must be ReadWriteMany (pods on many nodes share it)")
    sim = one(docs, "simulate-job.yaml", "Job")
    render = one(docs, "render-job.yaml", "Job")
    for name, job in [("simulate-job.yaml", sim), ("render-job.yaml", render)]:
        pod = job["spec"]["template"]["spec"]
        if pod.get("restartPolicy") != "Never":
            problems.append(f"{name}: restartPolicy must be Never (a retried pod starts afresh)")
        claims = [v.get("persistentVolumeClaim", {}).get("claimName") for v in pod.get("volumes", [])]
        if claim_name not in claims:
            problems.append(f"{name}: does not mount the claim {claim_name!r} of volume.yaml")
    sim_cmd = " ".join(sim["spec"]["template"]["spec"]["containers"][0]["command"])
    if " simulate" not in sim_cmd:
        problems.append("simulate-job.yaml: the command does not run `wisp simulate`")
    spec = render["spec"]
    if spec.get("completionMode") != "Indexed":
        problems.append("render-job.yaml: completionMode must be Indexed")
    container = spec["template"]["spec"]["containers"][0]
    render_cmd = " ".join(container.get("command", []) + container.get("args", []))
    env = {e["name"]: e.get("value") for e in container.get("env", [])}
    if env.get("SHARDS") != str(spec.get("completions")):
        problems.append(
            f"render-job.yaml: SHARDS is {env.get('SHARDS')!r}, completions is {spec.get('completions')}: they must be equal"
        )
    if '--shard "$((JOB_COMPLETION_INDEX + 1))/$SHARDS"' not in render_cmd:
        problems.append("render-job.yaml: the command must pass --shard \"$((JOB_COMPLETION_INDEX + 1))/$SHARDS\"")
    cache_out = flag_value(sim_cmd, "--out")
    cache_in = flag_value(render_cmd, "--cache")
    if cache_out is None or cache_out != cache_in:
        problems.append(f"render-job.yaml reads the cache {cache_in!r}, simulate-job.yaml writes {cache_out!r}")
    for flag in ["--hairstyle"]:
        if flag_value(sim_cmd, flag) != flag_value(render_cmd, flag):
            problems.append(f"{flag} differs between the simulate and render Jobs")
    return problems


def main():
    docs = load()
    problems = schema_problems(docs) + rule_problems(docs)
    for p in problems:
        print("error:", p)
    if problems:
        return 1
    print(f"deploy check: {len(docs)} manifests ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
