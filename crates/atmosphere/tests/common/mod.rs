pub mod lowtran;
