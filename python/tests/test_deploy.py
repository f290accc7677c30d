"""deploy/k8s/job.yaml checked against the Kubernetes API's own object models (the official
Python client's V1Job schema: every field known, of the declared type), and against what
`hatchery batch` needs from it; the Dockerfile builds the command the Job runs."""

import pathlib

import pytest

yaml = pytest.importorskip("yaml", reason="PyYAML (pip install pyyaml)")
kubernetes = pytest.importorskip("kubernetes", reason="the Kubernetes client (pip install kubernetes)")

PRIMITIVES = {"str": str, "int": int, "bool": bool, "float": (int, float), "object": object,
              "datetime": str, "date": str, "bytes": str}


def check(value, type_name, where, models):
    """Every key of `value` is a field of the model `type_name`, recursively."""
    # The client writes container types as List[X] and Dict[str, X] (older ones: list[X],
    # dict(str, X)).
    if type_name.lower().startswith("list["):
        assert isinstance(value, list), f"{where}: expected a list"
        for i, v in enumerate(value):
            check(v, type_name[5:-1], f"{where}[{i}]", models)
    elif type_name.lower().startswith(("dict[", "dict(")):
        assert isinstance(value, dict), f"{where}: expected a mapping"
        inner = type_name[5:-1].split(", ", 1)[1]
        for k, v in value.items():
            check(v, inner, f"{where}.{k}", models)
    elif type_name in PRIMITIVES:
        assert isinstance(value, PRIMITIVES[type_name]), f"{where}: expected {type_name}, got {value!r}"
    else:
        cls = getattr(models, type_name)
        by_json = {json: attr for attr, json in cls.attribute_map.items()}
        assert isinstance(value, dict), f"{where}: expected a {type_name} mapping"
        for key, v in value.items():
            assert key in by_json, f"{where}: `{key}` is not a field of {type_name}"
            check(v, cls.openapi_types[by_json[key]], f"{where}.{key}", models)


def test_the_indexed_job_matches_the_kubernetes_schema(repo):
    doc = yaml.safe_load((repo / "deploy" / "k8s" / "job.yaml").read_text())
    assert doc["apiVersion"] == "batch/v1" and doc["kind"] == "Job"
    check(doc, "V1Job", "job.yaml", kubernetes.client.models)
    spec = doc["spec"]
    assert spec["completionMode"] == "Indexed"
    container = spec["template"]["spec"]["containers"][0]
    env = {e["name"]: e["value"] for e in container["env"]}
    assert int(env["HATCHERY_SHARD_COUNT"]) == spec["completions"], "every index has its shard"
    assert container["args"][0] == "batch"
    job = repo / "jobs" / container["args"][1].split("/", 1)[1]
    assert job.exists(), f"the Job renders {job}, which the image copies from jobs/"
    mounts = {m["mountPath"] for m in container["volumeMounts"]}
    assert container["args"][container["args"].index("--out") + 1] in mounts


def test_a_schema_error_is_caught(repo):
    doc = yaml.safe_load((repo / "deploy" / "k8s" / "job.yaml").read_text())
    doc["spec"]["completionsMode"] = "Indexed"  # a typo
    with pytest.raises(AssertionError, match="completionsMode"):
        check(doc, "V1Job", "job.yaml", kubernetes.client.models)


def test_the_dockerfile_builds_and_ships_what_the_job_runs(repo):
    text = (repo / "deploy" / "k8s" / "Dockerfile").read_text()
    assert "cargo build --release --bin hatchery" in text
    assert "COPY jobs /opt/hatchery/jobs" in text and 'ENTRYPOINT ["hatchery"]' in text
    assert pathlib.Path(repo / "jobs" / "default_turntable.ron").exists()
