# Convenience targets for developers; the README's Quick start uses the scripts directly so it
# works on a machine that does not have make yet.
.PHONY: deps build demo test clean
deps:
	scripts/install-deps.sh
build:
	scripts/build.sh
demo:
	scripts/demo.sh
test:
	scripts/test.sh
clean:
	rm -rf build out
