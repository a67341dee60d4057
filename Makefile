# Shortcuts; the scripts are the source of truth (see README).
.PHONY: demo test build bench format clean
demo:
	bash scripts/demo.sh
test:
	bash scripts/test.sh
build:
	bash scripts/build.sh
bench: build
	python3 -m weft.bench render
format:
	clang-format -i $$(git ls-files '*.cpp' '*.h')
clean:
	rm -rf build out
