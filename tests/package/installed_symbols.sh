#!/bin/sh
# Prints every function the installed headers declare that no installed library defines (none
# when the API links): the declarations as GCC's Ada-spec dump lists them, against the symbols
# of the installed libraries and of the headers' own inline functions.
# Usage: installed_symbols.sh PREFIX WORK_DIR
set -eu
prefix=$1
work=$2
mkdir -p "$work"
cd "$work"
rm -f ./*.ads
echo '#include <hmblur/hmblur.h>' > all.cpp
g++ -std=c++20 -I"$prefix/include" -fdump-ada-spec -fsyntax-only all.cpp
grep -h -o 'External_Name => "[^"]*"' hmblur_*.ads | sed 's/External_Name => "//; s/"$//' | sort -u > declared.txt
g++ -std=c++20 -I"$prefix/include" -fkeep-inline-functions -c all.cpp -o all.o
{ nm --defined-only all.o; for lib in "$prefix"/lib*/libhmb*.a; do nm --defined-only "$lib"; done; } |
  awk 'NF == 3 && $2 ~ /[TWVBDR]/ { print $3 }' | sort -u > defined.txt
comm -23 declared.txt defined.txt | c++filt > missing.txt
# Constants (no parameter list) and deleted or defaulted operators have nothing to link.
grep '(' missing.txt | grep -v 'operator=(\|operator==(' || true
