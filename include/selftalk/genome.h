/* SPDX-License-Identifier: MIT
 * libselftalk: genotypes - 16-bit genes, the stable gene layout of SPEC §4, the genome text
 * format, and growing a primitive-stage genotype into an integrated-stage one.
 *
 * Owns: stGenome (a fixed-size value, caller-owned) and stGenomeSet (a heap array of
 * genotypes read from a file; freed with st_genome_set_free). */
#ifndef SELFTALK_GENOME_H
#define SELFTALK_GENOME_H

#include <stdint.h>
#include <stdio.h>

#include "selftalk/base.h"
#include "selftalk/rng.h"
#include "selftalk/study.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Network sizes (SPEC §4). The network is fixed-size: these are part of the gene layout. */
#define ST_NET_NIN 25      /* inputs of the base network */
#define ST_NET_NHID 15     /* hidden neurons */
#define ST_NET_NOUT 13     /* outputs of the base network */
#define ST_NET_NDOF 12     /* actuated DOF: outputs 0..11 */
#define ST_NET_NLING ST_NPRIM /* linguistic units: one a primitive's word */
#define ST_NET_NFOCUS 3    /* focus-vector inputs 18..20 */
#define ST_NET_NDIRECT 9   /* outputs 0..8 (torso + arm) fed directly by the focus inputs */
#define ST_NET_IN_TOUCH 12 /* first touch input */
#define ST_NET_IN_FOCUS 18 /* first focus input */
#define ST_NET_IN_LING 21  /* first linguistic input */
#define ST_NET_IN_SECONDARY 25 /* secondary linguistic input (integrated networks) */
#define ST_NET_OUT_FOCUS 12    /* focus output */
#define ST_NET_MAX_IN 26
#define ST_NET_MAX_OUT 17  /* 13 outputs + 4 linguistic values */

/* Network architectures: base (primitive stages), type A (self talk: linguistic outputs),
 * type B (hidden linguistic memory feeding the hidden layer). */
typedef enum stNetArch { ST_ARCH_BASE = 0, ST_ARCH_A, ST_ARCH_B, ST_ARCH_COUNT } stNetArch;

/* "base", "A" or "B". */
ST_API const char *st_arch_name(stNetArch arch);
/* Parses "base", "A" or "B" (case-insensitive); returns -1 for anything else. */
ST_API int st_arch_parse(const char *name);
/* Genes of an architecture: 612, 696 or 756. */
ST_API int st_arch_ngenes(stNetArch arch);

/* Gene layout (SPEC §4 table): first index of each block and the index of one gene.
 * Within a block the index runs target-major. */
#define ST_GENES_BASE 612
#define ST_GENES_A 696
#define ST_GENES_B 756
#define ST_GENOME_MAX_GENES 756

#define ST_GENE_IH0 0     /* input -> hidden, 25 x 15 */
#define ST_GENE_HO0 375   /* hidden -> output, 15 x 13 */
#define ST_GENE_FO0 570   /* focus input -> torso/arm outputs, 3 x 9 */
#define ST_GENE_BIAS0 597 /* hidden biases, 15 */
#define ST_GENE_HL0 612   /* hidden -> linguistic cluster, 15 x 4 */
#define ST_GENE_LL0 672   /* linguistic recurrent, 4 x 4 */
#define ST_GENE_DECAY0 688 /* decay factor of the linguistic cluster, 4 */
#define ST_GENE_SL0 692   /* secondary input -> linguistic cluster, 4 */
#define ST_GENE_LH0 696   /* hidden linguistic -> hidden (type B), 4 x 15 */

#define ST_GENE_IH(h, i) (ST_GENE_IH0 + (h) * ST_NET_NIN + (i))
#define ST_GENE_HO(k, h) (ST_GENE_HO0 + (k) * ST_NET_NHID + (h))
#define ST_GENE_FO(k, f) (ST_GENE_FO0 + (k) * ST_NET_NFOCUS + (f))
#define ST_GENE_BIAS(h) (ST_GENE_BIAS0 + (h))
#define ST_GENE_HL(m, h) (ST_GENE_HL0 + (m) * ST_NET_NHID + (h))
#define ST_GENE_LL(m, n) (ST_GENE_LL0 + (m) * ST_NET_NLING + (n)) /* link n -> m */
#define ST_GENE_DECAY(m) (ST_GENE_DECAY0 + (m))
#define ST_GENE_SL(m) (ST_GENE_SL0 + (m))
#define ST_GENE_LH(h, m) (ST_GENE_LH0 + (h) * ST_NET_NLING + (m))

/* One genotype: genes in layout order, 16 bits each, most significant bit first. */
typedef struct stGenome {
  int ngenes;
  uint16_t gene[ST_GENOME_MAX_GENES];
} stGenome;

/* Decoded value of a gene: v = -1 + 2u/65535, so 0 -> -1 and 65535 -> +1. */
ST_API double st_gene_value(uint16_t u);

/* Bit b of a genotype, counting from the most significant bit of gene 0 (SPEC §4). */
ST_API int st_genome_bit(const stGenome *g, int b);
ST_API void st_genome_flip_bit(stGenome *g, int b);

/* Fills ngenes genes with fair coin flips drawn from rng. */
ST_API void st_genome_random(stGenome *g, int ngenes, stRng *rng);

/* Grows a 612-gene genotype to the integrated architecture (SPEC §4, thesis §2.9.2): the
 * blocks 612..695 get random genes from rng (fair coin flips); for type B the block 696..755
 * is set to typeb_init (32768 in the thesis protocol: v = 1/65535, near zero). Genes already
 * present are copied unchanged. Returns ST_ERR_ARG if `in` has not 612 genes or arch is base. */
ST_API stStatus st_genome_grow(const stGenome *in, stNetArch arch, uint16_t typeb_init, stRng *rng,
                        stGenome *out, char *err, size_t errsz);

/* Mutable-gene mask for the integrated stage: 0 for the frozen primitive genes (< 612),
 * 1 for the new ones, up to ngenes. mask must hold ST_GENOME_MAX_GENES bytes. */
ST_API void st_genome_mask_new_genes(uint8_t *mask, int ngenes);

/* ---- genome text format (SPEC §4) ----
 * Lines starting with '#' are comments or metadata ("# genes 612", "# fitness 123.4",
 * "# generation 7"); every other non-empty line is one genotype, 4 lower-case hex digits per
 * gene, no separators. Metadata "# fitness" and "# generation" apply to the next genotype. */

typedef struct stGenomeSet {
  int count;
  stGenome *genome;    /* count genotypes */
  double *fitness;     /* count values; NAN where the file gave none */
  int *generation;     /* count values; -1 where the file gave none */
} stGenomeSet;

/* Reads every genotype of a file (through st_file_read: at most ST_FILE_MAX bytes, no NUL
 * byte). Each must have 612, 696 or 756 genes (or, when expect_genes > 0, exactly that many),
 * agreeing with any "# genes" line; "# fitness" and "# generation" values must parse. Errors
 * name the file and line: "FILE:LINE: genotype: non-hex character 'x' at column 17 (expected 4
 * lower-case hex digits per gene)". On success the caller frees set with st_genome_set_free. */
ST_API stStatus st_genome_set_read(const char *path, int expect_genes, stGenomeSet *set, char *err,
                            size_t errsz);
ST_API void st_genome_set_free(stGenomeSet *set);

/* Writes one genotype line (no metadata) to f. */
ST_API int st_genome_write_line(FILE *f, const stGenome *g);

/* Writes "# genes N", optional "# generation G" (g >= 0) and "# fitness F" (finite) lines,
 * then the genotype line. Returns 0 on success, -1 on a write error. */
ST_API int st_genome_write(FILE *f, const stGenome *g, int generation, double fitness);

/* Writes a whole set to path atomically (temporary file, then rename): the file is either
 * the old one or the complete new one, never a torn write. Nullable: fitness, generation. */
ST_API stStatus st_genome_set_save(const char *path, const stGenome *g, int count, const double *fitness,
                            const int *generation, char *err, size_t errsz);

#ifdef __cplusplus
}
#endif

#endif
